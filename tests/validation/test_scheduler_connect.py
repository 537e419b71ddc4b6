"""``validate --scheduler ADDRESS`` ends with one line and a documented exit code whatever
answers at ADDRESS: nothing, bytes that are not dask, or an address scheme it cannot use;
the whole connection is bounded by ``SCHEDULER_TIMEOUT``."""

from __future__ import annotations

import socket
import threading
import time

import pytest

pytest.importorskip("distributed", reason="the 'cluster' extra is not installed")

import validation.cli as cli  # noqa: E402
import validation.cluster as cluster  # noqa: E402


def _server(answer: bytes | None) -> int:
    """A TCP server on a free port that accepts every connection and then sends
    ``answer`` (``None``: never a byte)."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(8)
    held = []

    def loop():
        while True:
            conn, _ = srv.accept()
            held.append(conn)
            if answer is not None:
                conn.sendall(answer)

    threading.Thread(target=loop, daemon=True).start()
    return srv.getsockname()[1]


def _validate(address, tmp_path, capsys):
    t0 = time.monotonic()
    code = cli.main(["validate", "--quick", "--case", "nh-d-e", "--out", str(tmp_path / "r"),
                     "--no-progress", "--scheduler", address])
    err = capsys.readouterr().err
    return code, err, time.monotonic() - t0


def test_a_silent_peer_is_one_line_and_exit_3_within_the_limit(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(cluster, "SCHEDULER_TIMEOUT", 1.0)
    port = _server(None)
    code, err, wall = _validate(f"tcp://127.0.0.1:{port}", tmp_path, capsys)
    assert code == 3 and err.count("\n") == 1, err
    assert "no dask scheduler answered within 1 s" in err
    # the limit plus the join's slack of 2 s, with 5 s for a loaded machine
    assert wall < 1.0 + 2.0 + 5.0


def test_a_peer_answering_other_bytes_is_one_line_and_exit_3(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(cluster, "SCHEDULER_TIMEOUT", 1.0)
    port = _server(b"HTTP/1.1 200 OK\r\n\r\nnot dask" * 50)
    code, err, _ = _validate(f"127.0.0.1:{port}", tmp_path, capsys)
    assert code == 3 and err.count("\n") == 1, err
    assert "no dask scheduler" in err and "Traceback" not in err


@pytest.mark.parametrize("scheme", ["tls", "ucx", "inproc"])
def test_an_unsupported_scheme_is_one_line_and_exit_2(scheme, tmp_path, capsys):
    code, err, _ = _validate(f"{scheme}://127.0.0.1:1", tmp_path, capsys)
    assert code == 2 and err.count("\n") == 1, err
    assert f"{scheme}:// is not supported" in err
