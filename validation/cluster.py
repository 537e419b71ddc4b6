"""The dask.distributed cluster of ``--scheduler local|ADDRESS`` (``validate`` and
``clamp-zone units``): a LocalCluster or a connection to a scheduler, bounded in time."""

from __future__ import annotations

import logging
import threading

__all__ = ["SCHEDULER_TIMEOUT", "dask_executor", "check_scheduler"]


def _one_line(text) -> str:
    return " ".join(str(text).split())


#: seconds that ``--scheduler ADDRESS`` waits for the scheduler in all (connection,
#: handshake, the first answer); past them the command ends with one line and exit code 3
SCHEDULER_TIMEOUT = 30.0


def check_scheduler(address: str) -> None:
    """``ValueError`` naming ``--scheduler`` unless ``address`` is ``local`` or a TCP
    address (``tcp://HOST:PORT`` or ``HOST:PORT``): checked before anything is written."""
    if not address.strip():
        raise ValueError("--scheduler must be a scheduler address or 'local', got ''")
    scheme = address.split("://", 1)[0].lower() if "://" in address else "tcp"
    if address != "local" and scheme != "tcp":
        raise ValueError(f"--scheduler must be a dask scheduler address tcp://HOST:PORT (or "
                         f"HOST:PORT) or 'local'; {scheme}:// is not supported (TLS needs "
                         f"security settings, UCX its own package), got {address!r}")


def dask_executor(address: str, jobs: int):
    """``(client, cluster)`` of a dask.distributed scheduler ``address`` or, for
    ``"local"``, a LocalCluster of ``jobs`` single-threaded worker processes (``cluster``
    is ``None`` for an address).

    Raises
    ------
    ValueError
        dask.distributed is not installed, or ``address`` is not ``local`` or a TCP address.
    OSError
        No scheduler answered at ``address`` within :data:`SCHEDULER_TIMEOUT`.
    """
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise ValueError(f"--scheduler needs dask.distributed (pip install -e '.[cluster]'), "
                         f"got --scheduler {address} without it") from None
    if address == "local":
        # a dashboard on a free port of this machine: no warning when 8787 is taken; the
        # workers log errors only (a task cancelled by SIGTERM is said by the one line)
        cluster = LocalCluster(n_workers=jobs, threads_per_worker=1, processes=True,
                               dashboard_address="127.0.0.1:0", silence_logs=logging.ERROR)
        return Client(cluster), cluster
    check_scheduler(address)
    box: dict = {}

    def connect():
        try:
            box["client"] = Client(address, timeout=f"{SCHEDULER_TIMEOUT:g}s")
        except BaseException as exc:   # reported by the caller's thread, one line
            box["error"] = exc

    # the whole connection within SCHEDULER_TIMEOUT: a peer that accepts the connection
    # and never answers (or answers what is not dask) must not hang the command
    worker = threading.Thread(target=connect, name="dask-connect", daemon=True)
    worker.start()
    worker.join(SCHEDULER_TIMEOUT + 2.0)
    if "client" in box:
        return box["client"], None
    exc = box.get("error")
    if isinstance(exc, ValueError) and "://" not in address and ":" not in address:
        raise ValueError(f"--scheduler must be a dask scheduler address (tcp://HOST:PORT) or "
                         f"'local', got {address!r} ({_one_line(exc)})") from None
    if exc is None:
        raise OSError(None, f"no dask scheduler answered within {SCHEDULER_TIMEOUT:g} s",
                      address)
    raise OSError(None, f"no dask scheduler there ({type(exc).__name__}: "
                        f"{_one_line(exc)[:200]})", address)
