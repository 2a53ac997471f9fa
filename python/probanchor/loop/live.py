"""The live world model: a run answers Prolog queries on its world model while it runs
(``anchoring run --serve PORT``).

A query server on localhost (HTTP, JSON) that a robot's other programs ask, as they would
call a service: ``GET /query?q=hidden_under(Obj, Occ, P)`` (or the query as a POST body)
answers for the world model after the run's last whole frame, and says which frame that is;
``GET /frame`` gives the last frame done. The run's loop never waits for a query: when one
comes, the loop hands over the world model's facts at its next frame boundary (the facts of a
world file, ``prolog/shell/world.pl``), and a SWI-Prolog process of the server's own answers the
query on them, as ``anchoring shell`` would. The queries of that process are sandboxed
(``library(sandbox)``: reading the world model and ordinary computation, no files, no
processes, no changes) and limited in time and answers; it ends with the run (its input is a
pipe from the run).

    >>> from probanchor.loop.live import ask                         # doctest: +SKIP
    >>> ask("hidden_under(Obj, Occ, P)", port=7070)
    {'frame': 57, 'time': 11.4, 'answers': [{'Obj': 'ball_1', 'Occ': 'mug_1', 'P': 0.93}],
     'truncated': False, 'query': 'hidden_under(Obj, Occ, P)'}
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
import threading
import time as _time
import urllib.error
import urllib.parse
import urllib.request
from collections.abc import Callable
from dataclasses import dataclass
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

from bridge.resources import prolog_file  # (a pure module: no Prolog started)

#: The most answers one query gives (the answer says ``truncated`` when there were more).
MAX_ANSWERS = 1000
#: Seconds a query may take in Prolog.
TIME_LIMIT = 10.0
#: Seconds a query waits for the run's next frame boundary.
FRAME_WAIT = 60.0


class LiveError(RuntimeError):
    """A query that could not be answered (no frame yet, the run ended, bad query, ...)."""


@dataclass(frozen=True)
class Snapshot:
    """The world model after one whole frame, as the facts of a world file."""

    frame: int
    time: float
    text: str


def swipl_path() -> str:
    """The SWI-Prolog beside this Python (the project's ``.venv/bin/swipl``), else on PATH."""
    beside = Path(sys.executable).parent / "swipl"
    return str(beside) if beside.exists() else (shutil.which("swipl") or "swipl")


def prolog_string(text: str) -> str:
    """``text`` as a Prolog double-quoted string."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
    return f'"{escaped.replace(chr(13), chr(92) + "r").replace(chr(9), chr(92) + "t")}"'


class PrologAnswers:
    """A SWI-Prolog process running ``anchoring_world_ask:serve/0`` on world files; one query
    at a time. Started at the first query; ends when its input closes (this process ending)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._process: subprocess.Popen[str] | None = None
        self._loaded: int | None = None
        self._folder = Path(tempfile.mkdtemp(prefix="anchoring-live-"))

    def _start(self) -> subprocess.Popen[str]:
        if self._process is None or self._process.poll() is not None:
            goal = (f"consult({prolog_string(str(prolog_file('shell', 'world.pl')))}), "
                    f"consult({prolog_string(str(prolog_file('shell', 'world_ask.pl')))})")
            self._process = subprocess.Popen(
                [swipl_path(), "-q", "--no-signals", "-g", goal,
                 "-g", "anchoring_world_ask:serve", "-t", "halt"],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                text=True, encoding="utf-8", bufsize=1)
            self._loaded = None
        return self._process

    def _command(self, process: subprocess.Popen[str], command: str) -> dict[str, Any]:
        assert process.stdin is not None and process.stdout is not None
        process.stdin.write(command + "\n")
        process.stdin.flush()
        line = process.stdout.readline()
        if not line:
            raise LiveError("the query process ended (a query that exhausted its memory?)")
        return json.loads(line)

    def ask(self, snapshot: Snapshot, query: str, max_answers: int) -> dict[str, Any]:
        """The answers of ``query`` on ``snapshot`` (the dict of
        ``anchoring_world_ask:ask_json/3``)."""
        with self._lock:
            process = self._start()
            try:
                if self._loaded != snapshot.frame:
                    file = self._folder / "world.pl"
                    file.write_text(snapshot.text, encoding="utf-8")
                    loaded = self._command(process, f"load({prolog_string(str(file))}).")
                    if "error" in loaded:
                        raise LiveError(f"frame {snapshot.frame}: {loaded['error']}")
                    self._loaded = snapshot.frame
                return self._command(process, f"ask({prolog_string(query)}, {int(max_answers)},"
                                              f" {TIME_LIMIT!r}).")
            except (OSError, ValueError) as exc:  # a broken pipe, a line that is not JSON
                self._end()
                self._folder.mkdir(exist_ok=True)
                raise LiveError(f"the query process failed: {exc}") from None

    def close(self) -> None:
        """End the process (after the query under way) and remove its files."""
        with self._lock:
            self._end()

    def _end(self) -> None:
        if self._process is not None:
            process, self._process = self._process, None
            try:
                if process.stdin is not None:
                    process.stdin.close()
                process.wait(timeout=5)
            except (OSError, subprocess.TimeoutExpired):
                process.kill()
                process.wait()
        shutil.rmtree(self._folder, ignore_errors=True)


class LiveWorld:
    """A run's world model served on localhost while the run goes on.

    The run calls :meth:`frame_done` after each frame (with a function that writes the world
    model's facts, called only when a query waits for them) and :meth:`finish` at its end;
    the server's threads call :meth:`snapshot`.

    Parameters
    ----------
    port:
        The TCP port on 127.0.0.1 (0: any free one, then :attr:`port`).
    host:
        The address to listen on; only this machine's by default.
    """

    def __init__(self, port: int = 0, host: str = "127.0.0.1") -> None:
        self._cond = threading.Condition()
        self._latest: tuple[int, float] | None = None  # the last whole frame
        self._snapshot: Snapshot | None = None
        self._wanted = False
        self._ended = False
        self._failure: str | None = None  # why the last snapshot asked for was not made
        self._answers = PrologAnswers()
        self._server = ThreadingHTTPServer((host, port), _handler(self))
        self._server.daemon_threads = True
        self.host = host
        self.port = int(self._server.server_address[1])
        self._thread = threading.Thread(target=self._server.serve_forever, daemon=True,
                                        name="world-model-server")
        self._thread.start()

    @property
    def url(self) -> str:
        """The server's address, ``http://127.0.0.1:PORT``."""
        return f"http://{self.host}:{self.port}"

    # ------------------------------------------------------------------ the run's side
    def frame_done(self, frame: int, time: float, facts: Callable[[], list[str]]) -> None:
        """A frame is done: the world model is whole. ``facts`` (the world file's lines) is
        called here, in the run's thread, only when a query waits."""
        with self._cond:
            self._latest = (frame, time)
            if not self._wanted:
                return
        try:
            snapshot = Snapshot(frame, time, "\n".join(facts()) + "\n")
        except Exception as exc:  # the run goes on; the waiting queries are told
            with self._cond:
                self._failure = f"frame {frame}: the world model could not be read: {exc}"
                self._wanted = False
                self._cond.notify_all()
            return
        with self._cond:
            self._snapshot = snapshot
            self._failure = None
            self._wanted = False
            self._cond.notify_all()

    def finish(self, facts: Callable[[], list[str]] | None) -> None:
        """The run ended: its last world model (``facts``; None: none) answers from now on."""
        snapshot = None
        with self._cond:
            latest = self._latest
        if latest is not None and facts is not None:
            snapshot = Snapshot(*latest, "\n".join(facts()) + "\n")
        with self._cond:
            if snapshot is not None:
                self._snapshot = snapshot
            self._ended = True
            self._cond.notify_all()

    def close(self) -> None:
        """Stop serving and end the query process."""
        self.finish(None)
        self._server.shutdown()
        self._server.server_close()
        self._answers.close()

    # ------------------------------------------------------------------ the server's side
    def last_frame(self) -> tuple[int, float] | None:
        """The last whole frame and its time, or None before the first."""
        with self._cond:
            return self._latest

    def snapshot(self, wait: float = FRAME_WAIT) -> Snapshot:
        """The world model after the last frame done when this was called (or a later one):
        made at the run's next frame boundary.

        Parameters
        ----------
        wait:
            Seconds to wait for that boundary.

        Returns
        -------
        The snapshot; :class:`LiveError` when no frame came in ``wait`` seconds.
        """
        deadline = _time.monotonic() + wait
        with self._cond:
            needed = -1 if self._latest is None else self._latest[0]
            self._failure = None
            while self._snapshot is None or self._snapshot.frame < needed:
                if self._failure is not None:
                    raise LiveError(self._failure)
                if self._ended:
                    if self._snapshot is None:
                        raise LiveError("the run ended before its first frame")
                    break
                self._wanted = True
                left = deadline - _time.monotonic()
                if left <= 0 or not self._cond.wait(left):
                    if self._snapshot is not None and self._snapshot.frame >= needed:
                        break
                    raise LiveError(f"no frame boundary within {wait:g} s (is the run "
                                    "stalled?)")
            return self._snapshot

    def answer(self, query: str, max_answers: int = MAX_ANSWERS) -> dict[str, Any]:
        """The answers of a Prolog query on the world model after the last whole frame.

        Returns
        -------
        ``{"frame", "time", "query", "answers": [{Var: value}], "truncated"}``, or with
        ``"error"`` instead of the answers for a query Prolog refused (syntax, not
        sandbox-safe, an error, its time limit).
        """
        if not query.strip():
            raise LiveError("an empty query")
        snapshot = self.snapshot()
        reply = self._answers.ask(snapshot, query.strip().removesuffix("."), max_answers)
        return {"frame": snapshot.frame, "time": snapshot.time, "query": query, **reply}


def _handler(world: LiveWorld) -> type[BaseHTTPRequestHandler]:
    class Handler(BaseHTTPRequestHandler):
        server_version = "anchoring-world/1"

        def log_message(self, format: str, *args: Any) -> None:  # noqa: A002 - no access log
            pass

        def _reply(self, status: int, body: dict[str, Any]) -> None:
            data = (json.dumps(body) + "\n").encode("utf-8")
            self.send_response(status)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)

        def _local(self) -> bool:
            # a page in a browser may not ask through a name that points here (DNS rebinding)
            host = (self.headers.get("Host") or "").rsplit(":", 1)[0].strip("[]")
            return host in ("127.0.0.1", "localhost", "::1", world.host)

        def _serve(self, query: str | None, params: dict[str, list[str]]) -> None:
            path = urllib.parse.urlsplit(self.path).path
            if not self._local():
                self._reply(403, {"error": "asked through another host name"})
            elif path == "/frame":
                last = world.last_frame()
                self._reply(200, {"frame": None if last is None else last[0],
                                  "time": None if last is None else last[1]})
            elif path in ("/", "/query"):
                try:
                    most = int(params.get("max", [MAX_ANSWERS])[0])
                    reply = world.answer(query or "", max(1, min(most, MAX_ANSWERS)))
                except (LiveError, ValueError) as exc:
                    self._reply(503 if isinstance(exc, LiveError) else 400,
                                {"error": str(exc)})
                    return
                self._reply(400 if "error" in reply else 200, reply)
            else:
                self._reply(404, {"error": f"no {path}: ask /query?q=QUERY or /frame"})

        def do_GET(self) -> None:  # noqa: N802 - the http.server name
            params = urllib.parse.parse_qs(urllib.parse.urlsplit(self.path).query)
            self._serve(params.get("q", [None])[0], params)

        def do_POST(self) -> None:  # noqa: N802
            length = int(self.headers.get("Content-Length") or 0)
            body = self.rfile.read(min(length, 1 << 20)).decode("utf-8", errors="replace")
            params = urllib.parse.parse_qs(urllib.parse.urlsplit(self.path).query)
            self._serve(body, params)

    return Handler


def ask(query: str, port: int, host: str = "127.0.0.1", timeout: float = FRAME_WAIT + 30
        ) -> dict[str, Any]:
    """Ask a running ``anchoring run --serve PORT`` a Prolog query.

    Parameters
    ----------
    query:
        Prolog text, as at the world-model shell's prompt (``hidden_under(Obj, Occ, P)``).
    port, host:
        Where the run serves.
    timeout:
        Seconds to wait for the answer.

    Returns
    -------
    ``{"frame", "time", "query", "answers": [{Var: value}], "truncated"}``; a
    :class:`LiveError` with the server's message for a query it refused, or when nothing
    serves there.
    """
    request = urllib.request.Request(f"http://{host}:{port}/query", data=query.encode("utf-8"),
                                     headers={"Content-Type": "text/plain; charset=utf-8"})
    try:
        with urllib.request.urlopen(request, timeout=timeout) as response:  # noqa: S310
            return json.loads(response.read())
    except urllib.error.HTTPError as exc:
        try:
            message = json.loads(exc.read()).get("error", str(exc))
        except ValueError:
            message = str(exc)
        raise LiveError(f"{host}:{port}: {message}") from None
    except (urllib.error.URLError, OSError) as exc:
        reason = getattr(exc, "reason", exc)
        raise LiveError(f"{host}:{port}: no world model served there ({reason}); start one "
                        "with anchoring run ... --serve PORT") from None

