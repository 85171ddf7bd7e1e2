"""Client of the cosim coupling protocol (proto/coupling.proto, docs/protocol.md) for solvers written in Python.

The counterpart of common/coupling/client.h (Debian: python3-zmq, python3-protobuf). The generated coupling_pb2
is found by cosim.proto.
"""
import os
import threading
import time

import zmq

from .proto import coupling_pb2 as pb

PROTOCOL_VERSION = pb.PROTOCOL_VERSION_CURRENT
ROLES = {"fluid": pb.ROLE_FLUID, "solid": pb.ROLE_SOLID}


class CouplingError(RuntimeError):
    """Refusal, protocol error, lost coupler or a failure Stop, with the reason."""


def scene_hash(path, overrides=()):
    """FNV-1a 64 of the file bytes + '\\n--set ' + each override (common/coupling/scene_hash.h)."""
    h = 0xCBF29CE484222325
    with open(path, "rb") as f:
        data = f.read() + b"".join(("\n--set " + o).encode() for o in overrides)
    for c in data:
        h = ((h ^ c) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return "%016x" % h


def heartbeat_connect_endpoint(welcome_endpoint, data_endpoint):
    """Where the heartbeat connection goes: Welcome.heartbeat_endpoint, a wildcard tcp host (0.0.0.0, *, [::])
    replaced by the host of the data endpoint; empty: the data endpoint (docs/protocol.md, "Sockets")."""
    if not welcome_endpoint:
        return data_endpoint
    if welcome_endpoint.startswith("tcp://") and data_endpoint.startswith("tcp://"):
        host, port = welcome_endpoint[6:].rsplit(":", 1)
        if host in ("0.0.0.0", "*", "[::]"):
            return "tcp://%s:%s" % (data_endpoint[6:].rsplit(":", 1)[0], port)
    return welcome_endpoint


class Client:
    """One solver's connection to the coupler: handshake in the constructor, heartbeats in a thread, then
    next() / send_faces() / receive_faces() / send_samples() / receive_states() / propose_dt() in the order of
    docs/protocol.md ("Writing a solver client"); close() at the end."""

    def __init__(self, endpoint, token, role, scene_hash_, program="python", phase_names=(), connect_timeout=30.0,
                 restarted_from=0, restart_time=0.0, ranks=1):
        """restarted_from, restart_time: the cycle and time of the checkpoint set a restarted solver restored
        (docs/protocol.md, "Checkpoints"); the first DtDecision is then that of cycle restarted_from + 1.
        ranks: how many MPI ranks this connection speaks for (Hello.ranks, 1 to 1000000)."""
        if not 1 <= ranks <= 1000000:
            raise ValueError("ranks: %r, expected 1 to 1000000 MPI ranks" % (ranks,))
        self.endpoint, self.token, self.role = endpoint, token, ROLES[role]
        self.role_name = role
        self.cycle, self.time = (restarted_from, restart_time) if restarted_from > 0 else (-1, 0.0)
        self.ctx = zmq.Context()
        self.sock = self.ctx.socket(zmq.DEALER)
        self.sock.setsockopt(zmq.LINGER, 500)
        self.sock.connect(endpoint)
        self._last_return = time.monotonic()
        self._busy = 0.0  # work since the previous send, up to _last_return [s]
        self._lost = None
        self._stop = threading.Event()
        e = self._envelope()
        e.hello.role = self.role
        e.hello.scene_hash = scene_hash_
        e.hello.program = program
        e.hello.pid = os.getpid()
        e.hello.phase_names.extend(phase_names)
        e.hello.restarted_from = restarted_from
        e.hello.ranks = ranks
        self.sock.send(e.SerializeToString())
        w = self._receive("Welcome", connect_timeout)
        if w.WhichOneof("body") != "welcome":
            self._fail("expected Welcome, got %s" % w.WhichOneof("body"))
        if not w.welcome.accepted:
            raise CouplingError("coupler at %s refused %s: %s" % (endpoint, role, w.welcome.reason))
        self.timeout = w.welcome.timeout or 5.0
        self.mode = w.welcome.mode
        # SEQUENTIAL or PIPELINED (unspecified reads as pipelined): only a fluid's DtProposal moves with it
        self.scheme = w.welcome.scheme or pb.COUPLING_SCHEME_PIPELINED
        self.heartbeat_endpoint = heartbeat_connect_endpoint(w.welcome.heartbeat_endpoint, endpoint)
        self._hb = threading.Thread(target=self._heartbeat, args=(w.welcome.heartbeat_interval or 1.0,), daemon=True)
        self._hb.start()

    # --- internals -------------------------------------------------------------------------------------
    def _envelope(self):
        e = pb.Envelope()
        h = e.header
        h.protocol_version, h.cycle, h.time, h.sender, h.token = PROTOCOL_VERSION, self.cycle, self.time, self.role, self.token
        return e

    def _send(self, e):
        e.header.busy_seconds = self._busy + time.monotonic() - self._last_return
        self._busy = 0.0
        self.sock.send(e.SerializeToString())
        self._last_return = time.monotonic()

    def _fail(self, what):
        e = self._envelope()
        e.error.reason = what
        self.sock.send(e.SerializeToString())
        raise CouplingError("%s: %s" % (self.role_name, what))

    def _heartbeat(self, interval):
        s = self.ctx.socket(zmq.DEALER)
        s.setsockopt(zmq.LINGER, 0)
        s.connect(self.heartbeat_endpoint)  # the coupler's heartbeat thread (Welcome.heartbeat_endpoint)
        last_seen, next_send = time.monotonic(), 0.0
        while not self._stop.is_set():
            now = time.monotonic()
            if now >= next_send:
                e = self._envelope()
                e.heartbeat.SetInParent()
                s.send(e.SerializeToString())
                next_send = now + interval
            if s.poll(50):
                while s.poll(0):
                    s.recv()
                last_seen = time.monotonic()
            if time.monotonic() - last_seen > self.timeout:
                self._lost = "coupler at %s declared dead: no heartbeat for %.1f s (timeout %g s)" % (
                    self.endpoint, time.monotonic() - last_seen, self.timeout)
                break
        s.close()

    def _receive(self, expected, max_wait=0.0):
        start = time.monotonic()
        self._busy += start - self._last_return
        while not self.sock.poll(100):
            if self._lost:
                raise CouplingError(self._lost)
            if max_wait and time.monotonic() - start > max_wait:
                raise CouplingError("%s: no %s from the coupler at %s within %g s" % (
                    self.role_name, expected, self.endpoint, max_wait))
        frames = self.sock.recv_multipart()
        e = pb.Envelope()
        try:
            if len(frames) != 1:
                raise ValueError("%d frames" % len(frames))
            e.ParseFromString(frames[0])
        except Exception:
            self._fail("malformed message (%d bytes): not a cosim Envelope" % len(frames[0]))
        if not e.HasField("header") or e.WhichOneof("body") is None:
            self._fail("malformed message: no header or no body")
        if e.header.token != self.token:
            self._fail("%s with a wrong run token" % e.WhichOneof("body"))
        if e.WhichOneof("body") == "error":
            raise CouplingError("coupler reported an error: " + e.error.reason)
        return e

    def _expect(self, body):
        e = self._receive(body)
        kind = e.WhichOneof("body")
        if kind == "stop":
            raise CouplingError("coupler stopped the run while %s waited for %s: %s" % (self.role_name, body, e.stop.reason))
        if kind != body:
            self._fail("expected %s in cycle %d, got %s" % (body, self.cycle, kind))
        if e.header.cycle != self.cycle:
            self._fail("%s for cycle %d, expected cycle %d" % (body, e.header.cycle, self.cycle))
        self._last_return = time.monotonic()
        return getattr(e, body)

    # --- API (same order of calls as the C++ client) ---------------------------------------------------
    def next(self):
        """Returns ('advance', dt) | ('output', index) | ('checkpoint', directory) | ('stop', reason); raises on a
        failure Stop. After ('checkpoint', d): write the state into d as one file, then confirm_checkpoint."""
        e = self._receive("DtDecision, OutputRequest or Stop")
        self._last_return = time.monotonic()
        kind = e.WhichOneof("body")
        if kind == "stop":
            if e.stop.failure:
                raise CouplingError("coupler stopped the run: " + e.stop.reason)
            return "stop", e.stop.reason
        if kind == "dt_decision":
            if e.header.cycle != self.cycle + 1:
                self._fail("DtDecision for cycle %d, expected %d" % (e.header.cycle, self.cycle + 1))
            self.cycle, self.time = e.header.cycle, e.header.time
            return "advance", e.dt_decision.dt
        if kind == "output_request":
            self.output_time = e.header.time
            return "output", e.output_request.index
        if kind == "checkpoint_request":
            if e.header.cycle != self.cycle:
                self._fail("CheckpointRequest for cycle %d, expected %d" % (e.header.cycle, self.cycle))
            return "checkpoint", e.checkpoint_request.directory
        self._fail("expected DtDecision, OutputRequest, CheckpointRequest or Stop, got %s" % kind)

    def confirm_checkpoint(self, part, size):
        """This solver's part (a file name in the set directory, `size` bytes) is written."""
        e = self._envelope()
        e.checkpoint_written.part, e.checkpoint_written.bytes = part, size
        self._send(e)

    def send_faces(self, faces):
        """faces: dict with dim, centre, normal, area, velocity, normal_stress, impedance (flat lists), and
        optionally nodes_per_face, vertex_position, face_vertex."""
        e = self._envelope()
        f = e.faces
        f.dim, f.count = faces["dim"], len(faces["area"])
        for k in ("centre", "normal", "area", "velocity", "normal_stress", "impedance"):
            getattr(f, k).extend(faces[k])
        if faces.get("nodes_per_face"):  # vertex data: needed by a fluid that embeds the faces
            f.nodes_per_face = faces["nodes_per_face"]
            f.vertex_position.extend(faces["vertex_position"])
            f.face_vertex.extend(faces["face_vertex"])
        self._send(e)

    def receive_faces(self):
        return self._expect("faces")

    def send_samples(self, s):
        e = self._envelope()
        m = e.samples
        m.count, m.phases = s["count"], s["phases"]
        for k in ("alpha", "rho", "normal_velocity", "pressure", "impedance", "wetted"):
            getattr(m, k).extend(s[k])
        self._send(e)

    def receive_states(self):
        return self._expect("states")

    def propose_dt(self, dt):
        e = self._envelope()
        e.dt_proposal.dt = dt
        self._send(e)

    def report_error(self, reason):
        try:
            e = self._envelope()
            e.error.reason = reason
            self.sock.send(e.SerializeToString(), zmq.NOBLOCK)
        except Exception:
            pass

    def close(self):
        self._stop.set()
        if getattr(self, "_hb", None):
            self._hb.join()
        self.sock.close()
        self.ctx.term()


__all__ = ["Client", "CouplingError", "PROTOCOL_VERSION", "ROLES", "heartbeat_connect_endpoint", "pb", "scene_hash"]
