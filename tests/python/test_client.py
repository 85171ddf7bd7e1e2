"""cosim.client: scene hash, the cosim_client shim, a handshake with a stand-in coupler, and where the generated
coupling_pb2 is taken from."""
import os
import shutil
import subprocess
import threading

import pytest
import zmq

import cosim.client as client
from cosim.rigid_piston import box_faces
from support import PACKAGE_PARENT, PYTHON, REPO

pb = client.pb


def test_scene_hash_is_fnv1a_64(tmp_path):
    empty, a = tmp_path / "empty.yaml", tmp_path / "a.yaml"
    empty.write_bytes(b"")
    a.write_bytes(b"a")
    assert client.scene_hash(empty) == "cbf29ce484222325"  # FNV-1a 64 of "" and "a"
    assert client.scene_hash(a) == "af63dc4c8601ec8c"
    with_set = tmp_path / "with_set.yaml"
    with_set.write_bytes(b"a\n--set k=v")
    assert client.scene_hash(a, ["k=v"]) == client.scene_hash(with_set)
    assert client.scene_hash(a, ["k=v"]) != client.scene_hash(a, ["k=w"])


def test_cosim_client_shim_is_the_same_module_content():
    import cosim_client
    assert cosim_client.scene_hash is client.scene_hash
    assert cosim_client.Client is client.Client and cosim_client.CouplingError is client.CouplingError
    assert cosim_client.pb is pb and cosim_client.PROTOCOL_VERSION == pb.PROTOCOL_VERSION_CURRENT == 7


class StandInCoupler(threading.Thread):
    """A ROUTER that answers the first Hello with Welcome (accepted or not), then sends DtDecision of cycle 0,
    takes the faces, and sends Stop. Records what it received."""

    def __init__(self, endpoint, token, accept=True):
        super().__init__(daemon=True)
        self.endpoint, self.token, self.accept = endpoint, token, accept
        self.ctx = zmq.Context()
        self.router = self.ctx.socket(zmq.ROUTER)
        self.router.setsockopt(zmq.LINGER, 0)
        self.router.bind(endpoint)
        self.beats = self.ctx.socket(zmq.ROUTER)  # its heartbeat socket (Welcome.heartbeat_endpoint)
        self.beats.setsockopt(zmq.LINGER, 0)
        self.beats.bind(endpoint + "-hb")
        self.received, self.error = [], None

    def envelope(self, cycle=0):
        e = pb.Envelope()
        h = e.header
        h.protocol_version, h.cycle, h.sender, h.token = pb.PROTOCOL_VERSION_CURRENT, cycle, pb.ROLE_COUPLER, self.token
        return e

    def receive(self, body):
        """The next message of the data connection with this body (heartbeats skipped)."""
        while True:
            if not self.router.poll(10_000):
                raise TimeoutError(f"no {body}")
            ident, data = self.router.recv_multipart()
            e = pb.Envelope()
            e.ParseFromString(data)
            if e.WhichOneof("body") == "heartbeat":
                continue
            assert e.WhichOneof("body") == body, e.WhichOneof("body")
            self.received.append(e)
            return ident, e

    def run(self):
        try:
            ident, _ = self.receive("hello")
            w = self.envelope(-1)
            w.welcome.accepted, w.welcome.reason = self.accept, "" if self.accept else "another scene"
            w.welcome.timeout, w.welcome.heartbeat_interval = 5.0, 0.1
            w.welcome.mode, w.welcome.scheme = pb.COUPLING_MODE_ROBIN, pb.COUPLING_SCHEME_SEQUENTIAL
            w.welcome.heartbeat_endpoint = self.endpoint + "-hb"
            self.router.send_multipart([ident, w.SerializeToString()])
            if not self.accept:
                return
            d = self.envelope(0)
            d.dt_decision.dt, d.dt_decision.target_time = 0.0, 0.0
            self.router.send_multipart([ident, d.SerializeToString()])
            self.receive("faces")
            s = self.envelope(0)
            s.stop.reason, s.stop.failure = "end time reached", False
            self.router.send_multipart([ident, s.SerializeToString()])
        except Exception as e:  # reported by the test
            self.error = e

    def heartbeats(self):
        """The Heartbeats that reached the heartbeat socket so far, waiting a little for the first."""
        got = []
        while self.beats.poll(2000 if not got else 0):
            _, data = self.beats.recv_multipart()
            e = pb.Envelope()
            e.ParseFromString(data)
            got.append(e)
        return got

    def close(self):
        self.join(10)
        self.router.close()
        self.beats.close()
        self.ctx.term()


def test_heartbeat_endpoint_takes_the_data_endpoints_host_for_a_wildcard():
    assert client.heartbeat_connect_endpoint("tcp://0.0.0.0:41234", "tcp://coupler:5555") == "tcp://coupler:41234"
    assert client.heartbeat_connect_endpoint("tcp://127.0.0.1:4", "tcp://localhost:5") == "tcp://127.0.0.1:4"
    assert client.heartbeat_connect_endpoint("ipc:///d/c-hb.sock", "ipc:///d/c.sock") == "ipc:///d/c-hb.sock"
    assert client.heartbeat_connect_endpoint("", "ipc:///d/c.sock") == "ipc:///d/c.sock"


def test_handshake_cycle_and_stop(tmp_path):
    coupler = StandInCoupler(f"ipc://{tmp_path}/c.sock", "t0ken")
    coupler.start()
    c = client.Client(f"ipc://{tmp_path}/c.sock", "t0ken", "solid", "0123456789abcdef", program="test", ranks=3)
    try:
        assert c.scheme == pb.COUPLING_SCHEME_SEQUENTIAL and c.mode == pb.COUPLING_MODE_ROBIN
        beats = coupler.heartbeats()  # on the socket the Welcome named, not the data socket
        assert beats and all(b.WhichOneof("body") == "heartbeat" and b.header.token == "t0ken" for b in beats)
        assert c.next() == ("advance", 0.0) and c.cycle == 0
        c.send_faces(box_faces(2, -1.0, 0.0, [0.0], [0.8], 0.0))
        assert c.next() == ("stop", "end time reached")
    finally:
        c.close()
        coupler.close()
    assert coupler.error is None
    hello, faces = coupler.received[0], coupler.received[1]
    assert hello.hello.role == pb.ROLE_SOLID and hello.hello.scene_hash == "0123456789abcdef"
    assert hello.hello.program == "test" and hello.hello.pid == os.getpid()
    assert hello.header.token == "t0ken" and hello.header.protocol_version == pb.PROTOCOL_VERSION_CURRENT == 7
    assert hello.hello.ranks == 3  # the MPI ranks this connection speaks for (version 7)
    assert faces.faces.dim == 2 and faces.faces.count == 4 and faces.faces.nodes_per_face == 2
    assert list(faces.faces.normal[:2]) == [-1.0, 0.0] and faces.header.cycle == 0


def test_ranks_out_of_range_are_refused_before_connecting():
    for bad in (0, 1000001):
        with pytest.raises(ValueError, match="ranks: %d, expected 1 to 1000000" % bad):
            client.Client("ipc:///nonexistent/c.sock", "t0ken", "solid", "0" * 16, ranks=bad)


def test_refusal_names_the_reason(tmp_path):
    coupler = StandInCoupler(f"ipc://{tmp_path}/c.sock", "t0ken", accept=False)
    coupler.start()
    try:
        with pytest.raises(client.CouplingError, match="refused solid: another scene"):
            client.Client(f"ipc://{tmp_path}/c.sock", "t0ken", "solid", "0" * 16)
    finally:
        coupler.close()


# ------------------------------------------------------------------------------ where coupling_pb2 comes from


def fake_checkout(root, source_tree=True):
    """<root>/python/cosim: the package under test without its coupling_pb2.py (<root>/proto/coupling.proto makes
    it a source checkout)."""
    shutil.copytree(PACKAGE_PARENT / "cosim", root / "python" / "cosim",
                    ignore=shutil.ignore_patterns("__pycache__", "coupling_pb2.py"))
    if source_tree:
        (root / "proto").mkdir()
        (root / "proto" / "coupling.proto").write_text("")
    return root / "python"


def import_client(cwd):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    return subprocess.run([PYTHON, "-c", "import cosim.client as c; print(c.pb.__file__); print(c.pb.__name__)"],
                          cwd=cwd, env=env, capture_output=True, text=True, timeout=60)


def test_source_tree_without_a_build_says_build_first(tmp_path):
    python = fake_checkout(tmp_path)
    done = import_client(python)
    assert done.returncode != 0
    assert "ImportError" in done.stderr and "build first" in done.stderr
    # the rest of the package does not need it
    done = subprocess.run([PYTHON, "-c", "import cosim; print(cosim.read_run)"], cwd=python, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0 and "read_run" in done.stdout


def test_source_tree_takes_the_build_module(tmp_path):
    python = fake_checkout(tmp_path)
    build = tmp_path / "build" / "python"
    (build / "cosim").mkdir(parents=True)
    shutil.copy(pb.__file__, build / "cosim" / "coupling_pb2.py")
    done = import_client(python)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == [str(build / "cosim" / "coupling_pb2.py"), "cosim.coupling_pb2"]


def test_outside_a_source_tree_there_is_no_fallback(tmp_path):
    python = fake_checkout(tmp_path, source_tree=False)
    (tmp_path / "build" / "python" / "cosim").mkdir(parents=True)
    shutil.copy(pb.__file__, tmp_path / "build" / "python" / "cosim" / "coupling_pb2.py")
    done = import_client(python)
    assert done.returncode != 0 and "build first" in done.stderr


def test_the_repository_source_tree_imports(tmp_path):
    python = REPO / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    done = subprocess.run([PYTHON, "-c", "import cosim; print(cosim.read_run)"], cwd=python, env=env,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    if not (REPO / "build" / "python" / "cosim" / "coupling_pb2.py").is_file():
        pytest.skip(f"no build in {REPO / 'build'}")
    done = subprocess.run([PYTHON, "-c", "import cosim.client as c; print(c.scene_hash)"], cwd=python, env=env,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
