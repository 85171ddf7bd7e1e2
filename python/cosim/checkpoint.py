"""Checkpoint sets as a restarting solver reads them: a part is used only when it matches its set's manifest.

A set RUN/checkpoints/NNNNNNNNN/ holds one part per process and manifest.json, which records each part's size and
SHA-256 (`checksums`) and the set's cycle and time (docs/protocol.md, Checkpoints).
"""
import hashlib
import json
import os

MANIFEST = "manifest.json"


class CorruptCheckpoint(Exception):
    """A part or manifest that does not verify; the message names the file and what differs."""


def read_verified_part(directory, part):
    """The bytes of `part` in the set `directory`, after checking them against the set's manifest."""
    manifest_path = os.path.join(directory, MANIFEST)
    try:
        with open(manifest_path) as f:
            manifest = json.load(f)
        recorded = manifest["checksums"][part]
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise CorruptCheckpoint("%s: no checksum of %s (%s: %s)" % (manifest_path, part, type(e).__name__, e))
    path = os.path.join(directory, part)
    with open(path, "rb") as f:
        data = f.read()
    if len(data) != recorded.get("bytes"):
        raise CorruptCheckpoint("%s: %d bytes, the manifest recorded %s: the part is truncated or replaced"
                                % (path, len(data), recorded.get("bytes")))
    digest = hashlib.sha256(data).hexdigest()
    if digest != recorded.get("sha256"):
        raise CorruptCheckpoint("%s: SHA-256 %s, the manifest recorded %s: the part is corrupt"
                                % (path, digest, recorded.get("sha256")))
    return data
