"""Run the designer (``camgen serve``): uvicorn on 127.0.0.1, a free port unless one is asked for, until Ctrl-C."""
from __future__ import annotations

import importlib.util
import socket
from collections.abc import Callable
from pathlib import Path

from camgen.core.errors import SpecError
from camgen.designer.app import MAX_MESSAGE, make_app
from camgen.designer.session import inside

#: the only address served: this machine
HOST = "127.0.0.1"
#: the highest port asked for
MAX_PORT = 65535


def check_installed() -> None:
    """Refuse in one line, naming the extra to install, where the server library is missing."""
    missing = [m for m in ("starlette", "uvicorn") if importlib.util.find_spec(m) is None]
    if missing:
        raise SpecError(f"the designer needs {' and '.join(missing)}: pip install 'camgen[serve]'", "serve")


def listen(port: int | None) -> socket.socket:
    """A socket listening on 127.0.0.1 at ``port`` (0 or None: a free one the system picks)."""
    if port is not None and not 0 <= port <= MAX_PORT:
        raise SpecError(f"must be 0 to {MAX_PORT} (got {port})", "--port")
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    try:
        sock.bind((HOST, port or 0))
    except OSError as exc:
        sock.close()
        raise SpecError(f"cannot listen on {HOST}:{port}: {exc.strerror or exc}", "--port") from None
    sock.listen(16)
    return sock


def serve(root: Path, template: Path | None, port: int | None, started: Callable[[str], None]) -> None:
    """Serve the folder ``root`` until Ctrl-C (or SIGTERM), each tab opening ``template`` first; ``started`` is
    called with the page's address once the server listens (the command prints it and opens the browser)."""
    check_installed()
    import uvicorn

    root = root.resolve()
    name = None
    if template is not None:
        name = inside(root, str(template.resolve().relative_to(root)) if template.resolve().is_relative_to(root)
                      else str(template)).relative_to(root).as_posix()
    sock = listen(port)
    chosen = sock.getsockname()[1]
    config = uvicorn.Config(make_app(root, name, chosen), log_level="warning", ws_max_size=4 * MAX_MESSAGE,
                            lifespan="off", timeout_graceful_shutdown=5)
    server = uvicorn.Server(config)
    url = f"http://{HOST}:{chosen}/"
    original = server.startup

    async def startup(sockets: list[socket.socket] | None = None) -> None:
        await original(sockets=sockets)
        started(url)

    server.startup = startup                              # type: ignore[method-assign]
    try:
        server.run(sockets=[sock])
    except KeyboardInterrupt:      # uvicorn raises the Ctrl-C again once it has stopped: stopping is what was asked
        pass
    finally:
        sock.close()
