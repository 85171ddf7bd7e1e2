"""The coupling protocol client under its former module name: everything of cosim.client.

New code imports cosim.client; this module stays for the scripts and tests that `import cosim_client`.
"""
from cosim.client import PROTOCOL_VERSION, ROLES, Client, CouplingError, pb, scene_hash

__all__ = ["Client", "CouplingError", "PROTOCOL_VERSION", "ROLES", "pb", "scene_hash"]
