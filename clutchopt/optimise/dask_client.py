"""The connection to a Dask scheduler for ``clutchopt sweep --dask ADDRESS``, bounded in time whatever answers.

Only ``tcp://host:port`` is taken, and from Python the ``inproc://`` address of a scheduler in the same process (a
``LocalCluster(processes=False)``): ``tls://`` needs the cluster's certificates (distributed's security settings),
which clutchopt does not take, and ``inproc://`` of another process cannot be reached; each is refused by name, as
is any other scheme. Before ``distributed`` connects, the address is probed: a scheduler greets each
new connection first, with 8 bytes (native ``Q``, as distributed writes them) giving the length of its handshake,
then the handshake (a few hundred bytes of msgpack naming its compression, Python and pickle protocol). A web
server says nothing until asked, other servers greet with text or junk: each is refused in one line. The probe,
the client's connection, its handshake (which distributed reads without a limit) and its first exchange with the
scheduler all run within one deadline, ``DEADLINE_S``.
"""

from __future__ import annotations

import os
import re
import socket
import struct
import time

from clutchopt.errors import InputError

DEADLINE_S = 10.0  # the README's promise: an answer within 10 s, whatever listens at the address
DEFAULT_PORT = 8786  # a Dask scheduler's
GREETING_BYTES = 1 << 20  # a scheduler's handshake is a few hundred bytes
HANDSHAKE_KEYS = {"compression", "python", "pickle-protocol"}
REFUSED_SCHEMES = {
    "tls": "needs the cluster's TLS certificates and keys (distributed's security settings), which clutchopt does "
           "not take; reach the scheduler by its tcp:// address (e.g. through an SSH tunnel: ssh -L 8786:localhost:8786 "
           "HOST, then --dask tcp://localhost:8786)",
    "inproc": "names a scheduler inside another Python process (a LocalCluster with processes=False), which this "
              "one cannot reach; give its tcp:// address",
}


def connect(address: str, deadline_s: float = DEADLINE_S):
    """A ``distributed.Client`` of the scheduler at ``tcp://host:port``, connected within ``deadline_s`` seconds;
    a malformed address, one of another scheme, or one where no Dask scheduler answers in time is bad input."""
    in_process = _in_this_process(address)
    if not in_process:
        parse_address(address)
    try:
        from distributed import Client
    except ImportError:
        raise InputError("--dask", "needs dask.distributed (pip install 'clutchopt[dask]')") from None
    deadline = time.monotonic() + deadline_s
    if not in_process:
        probe_scheduler(address, deadline_s)

    class BoundedClient(Client):
        """A client whose whole start (connection, handshake, first exchange) ends by the deadline."""

        def start(self, **kwargs):
            super().start(callback_timeout=_left(deadline), **kwargs)

    try:
        return BoundedClient(address, timeout=_left(deadline))
    except Exception as exc:  # distributed's own errors, the deadline's TimeoutError, a handshake it cannot decode
        raise InputError("--dask", f"cannot connect to a Dask scheduler at {address} within {deadline_s:g} s "
                                   f"({type(exc).__name__}: {' '.join(str(exc).split())[:120]})") from None


def _in_this_process(address: str) -> bool:
    """Whether ``address`` is the ``inproc://host/pid/n`` address of a scheduler in this process (nothing to probe)."""
    match = re.fullmatch(r"inproc://[^/\s]+/(\d+)/\d+", address)
    return match is not None and int(match[1]) == os.getpid()


def parse_address(address: str) -> tuple[str, int]:
    """The host and port of ``tcp://host[:port]`` (port 8786 if not given); other schemes refused by name."""
    scheme, separator, rest = address.partition("://")
    if not separator or not scheme:
        raise InputError("--dask", f"expected an address like tcp://host:8786, got {address!r}")
    if scheme in REFUSED_SCHEMES:
        raise InputError("--dask", f"{scheme}:// {REFUSED_SCHEMES[scheme]}")
    if scheme != "tcp":
        raise InputError("--dask", f"{scheme[:20]}:// is not supported; give the scheduler's tcp:// address, e.g. "
                                   "tcp://host:8786")
    match = re.fullmatch(r"([^\s:/\[\]]+)(?::(\d{1,5}))?/?", rest)
    if match is None:
        raise InputError("--dask", f"expected an address like tcp://host:8786, got {address!r}")
    host, port = match[1], int(match[2] or DEFAULT_PORT)
    if not 0 < port < 65536:
        raise InputError("--dask", f"port {port} is out of range (1 to 65535)")
    return host, port


def probe_scheduler(address: str, timeout: float) -> None:
    """Check within ``timeout`` seconds that a Dask scheduler greets at ``tcp://host:port`` with its handshake."""
    deadline = time.monotonic() + timeout
    host, port = parse_address(address)
    try:
        connection = socket.create_connection((host, port), timeout=timeout)
    except TimeoutError:
        raise InputError("--dask", f"cannot reach a Dask scheduler at {address}: no answer within {timeout:g} s") \
            from None
    except OSError as exc:
        raise InputError("--dask", f"cannot reach a Dask scheduler at {address} ({exc.strerror or exc})") from None
    with connection:
        head = _receive(connection, 8, deadline, address, f"sent no Dask greeting within {timeout:g} s (a web "
                                                          "server?)")
        (length,) = struct.unpack("Q", head)
        if not 0 < length <= GREETING_BYTES:
            raise InputError("--dask", f"{address} is not a Dask scheduler: it greets with {head!r}")
        body = _receive(connection, length, deadline, address, f"announced a greeting of {length} bytes but did "
                                                               f"not send it within {timeout:g} s")
    if not _is_handshake(body):
        raise InputError("--dask", f"{address} is not a Dask scheduler: its greeting of {length} bytes is no Dask "
                                   f"handshake (it begins {body[:16]!r})")


def _receive(connection: socket.socket, count: int, deadline: float, address: str, silence: str) -> bytes:
    """``count`` bytes from ``connection`` by ``deadline``; silence or a closed connection refused in one line."""
    data = b""
    try:
        while len(data) < count:
            connection.settimeout(_left(deadline))
            chunk = connection.recv(min(count - len(data), 1 << 16))
            if not chunk:
                raise ConnectionError("the connection closed")
            data += chunk
    except TimeoutError:
        raise InputError("--dask", f"{address} is not a Dask scheduler: it accepted the connection but {silence}") \
            from None
    except OSError as exc:
        raise InputError("--dask", f"{address} closed the connection ({exc.strerror or exc}): not a Dask "
                                   "scheduler") from None
    return data


def _is_handshake(body: bytes) -> bool:
    """Whether ``body`` decodes, as distributed decodes it, to a scheduler's handshake."""
    from distributed.protocol import loads
    from distributed.protocol.utils import unpack_frames

    try:
        frames, more = unpack_frames(body, partial=True)
        message = loads(frames, deserialize=False)
    except Exception:  # junk fails to decode in many ways (struct, msgpack, UTF-8, recursion): none is a handshake
        return False
    return not more and isinstance(message, dict) and HANDSHAKE_KEYS <= message.keys()


def _left(deadline: float) -> float:
    """Seconds until ``deadline``; a TimeoutError once it has passed."""
    left = deadline - time.monotonic()
    if left <= 0:
        raise TimeoutError("the deadline passed")
    return left
