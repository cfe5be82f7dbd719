"""Command-line plumbing both ``camgen`` and ``linkgen`` use: the error contract, the family options.

Only command-line modules print or exit: a library call raises, and :func:`user_errors`
turns the project's errors into one line on stderr and exit code 2.
"""
from __future__ import annotations

import atexit
import contextlib
import functools
import gc
import os
import sys
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import click

from camgen.core.errors import CamgenError


def fixed(value: float, digits: int = 3) -> str:
    """``value`` with ``digits`` decimals for the console, never "-0.000" for a value that rounds to nothing."""
    text = f"{value:.{digits}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text


def fail(message: str) -> None:
    """Print ``error: <message>`` on one line to stderr and exit with code 2."""
    click.echo("error: " + " ".join(str(message).split()), err=True)
    sys.exit(2)


def echo_written(files: Mapping[str, str], directory: Path, warnings: Iterable[str] = ()) -> None:
    """A command's last lines: each of ``warnings`` as ``warning: ...``, then ``wrote <path>`` for each file
    written (``files``: the bundle's map of file names in ``directory``)."""
    for warning in warnings:
        click.echo(f"warning: {warning}")
    for name in files.values():
        click.echo(f"wrote {directory / name}")


#: the exit status of a command whose output's reader went away (``camgen ... | head``): 128 + SIGPIPE, what the
#: shell reports for a tool that signal ends
CLOSED_PIPE_STATUS = 141


def _stdout_to_devnull() -> None:
    """Point the standard output at the null device, so that the interpreter's last flush of what is left in its
    buffer finds no closed pipe (Python's advice: the signal module's "Note on SIGPIPE")."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):        # no descriptor (a test runner's stream): nothing to flush
        pass


def closed_pipe() -> None:
    """The reader of the standard output went away: end quietly, as a Unix tool does, with
    :data:`CLOSED_PIPE_STATUS` and no message."""
    _stdout_to_devnull()
    sys.exit(CLOSED_PIPE_STATUS)


def _flushed() -> bool:
    """Flush the standard output; False (and it pointed at the null device) where its reader went away."""
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        _stdout_to_devnull()
        return False
    return True


def user_errors(func: Callable[..., Any]) -> Callable[..., Any]:
    """Turn the project's errors, and the operating system's (a folder that cannot be written), into
    ``error: <one line>`` and exit code 2; a closed standard output (``| head``) ends the command quietly
    (:func:`closed_pipe`)."""
    @functools.wraps(func)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return func(*args, **kwargs)
        except CamgenError as exc:
            fail(str(exc))
        except BrokenPipeError as exc:
            if exc.filename is not None:                 # a file's, not the standard output's
                fail(f"{exc.filename}: {exc.strerror or exc}")
            closed_pipe()
        except OSError as exc:
            where = f"{exc.filename}: " if exc.filename else ""
            fail(f"{where}{exc.strerror or exc}")
    return wrapper


def one_design(func: Callable[..., Any]) -> Callable[..., Any]:
    """:func:`user_errors` for a command that makes one design (or one table), run with Python's cyclic garbage
    collector paused, and restored after.

    Such a command's time is mostly its start-up: importing several hundred modules (pydantic, ezdxf, numpy,
    shapely, ours), whose new objects would set off collection after collection, each walking all of them; and
    one design leaves little cyclic garbage. Measured on ``camgen build`` (DXF, STL, JSON): 45 ms less CPU of
    0.55 s, peak memory up 1 MB. Commands that loop over many designs (family, bench, synthesize) keep it."""
    @functools.wraps(func)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        if not gc.isenabled():
            return func(*args, **kwargs)
        gc.disable()
        try:
            return func(*args, **kwargs)
        finally:
            gc.enable()
    return user_errors(wrapper)


@functools.cache
def _freeze_at_exit() -> None:
    """At the interpreter's exit (registered once: the cache makes a second call do nothing), move every object
    still alive out of the collector's sight (:func:`gc.freeze`): the shutdown's own garbage collections then no
    longer walk every module's objects one last time, about 0.1 s of a build's CPU (measured); nothing is left
    unwritten, as every file is closed by then and the standard streams are flushed regardless. A program that
    calls a command's ``main`` in-process (rather than running the console script) gets the same at its exit."""
    atexit.register(gc.freeze)


#: the environment variables the BLAS libraries numpy and scipy load (OpenBLAS, MKL, BLIS) read their thread count
#: from, and the OpenMP one OpenBLAS falls back on: where a user has set any, a command leaves their choice alone
BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")


@contextlib.contextmanager
def one_blas_thread() -> Any:
    """Run a command with its BLAS libraries on one thread (unless the user has set their threads, see
    :data:`BLAS_THREADS`), restoring the environment after it.

    A command's arrays are small (a linkage's Jacobian, a synthesis' least squares of a few dozen unknowns): the
    threads OpenBLAS starts by default only spin, and on a busy machine wait for a core. Measured on ``linkgen
    synthesize`` of templates/synth-crank-rocker.toml with both cores busy: 2.98-3.05 s wall with the default
    threads against 2.70-2.81 s on one (idle, the same within the noise). The libraries read the variables
    when they load (numpy and scipy are imported inside the commands, after this), and the processes a command
    starts (a family's workers, a local Dask cluster's) inherit them; the library's own calls are left to their
    caller's choice."""
    if any(name in os.environ for name in BLAS_THREADS):
        yield
        return
    set_here = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")
    os.environ.update(dict.fromkeys(set_here, "1"))
    try:
        yield
    finally:
        for name in set_here:
            os.environ.pop(name, None)


class Commands(click.Group):
    """The top-level command group of both products: a usage error (a missing argument, an option's bad
    value, an unknown command) is one line naming the option, with exit code 2, like every other error; each
    command runs with its BLAS libraries on one thread (:func:`one_blas_thread`)."""

    def main(self, *args: Any, **kwargs: Any) -> Any:
        _freeze_at_exit()
        kwargs["standalone_mode"] = False
        try:
            try:
                with one_blas_thread():
                    result = super().main(*args, **kwargs)
                code = result if isinstance(result, int) else 0
            except click.exceptions.Exit as exc:          # --help, --version
                code = exc.exit_code
            except click.ClickException as exc:
                fail(exc.format_message())
            except click.exceptions.Abort:
                fail("aborted")
        except SystemExit:
            if isinstance(sys.stdout, click.utils.PacifyFlushWrapper):   # click met the closed pipe (printing help)
                closed_pipe()
            _flushed()                                    # an error's exit: its status stands, whatever the pipe
            raise
        except BrokenPipeError:                           # the error's own line met a closed pipe (2>&1 | head)
            closed_pipe()
        if not _flushed():                                # what is printed is written here at the latest
            closed_pipe()
        sys.exit(code)


def _apply(func: Callable[..., Any], decorators: tuple) -> Callable[..., Any]:
    for decorator in reversed(decorators):
        func = decorator(func)
    return func


def template_argument() -> Any:
    """The TEMPLATE argument: an existing TOML file."""
    return click.argument("template", type=click.Path(exists=True, dir_okay=False, path_type=Path))


def set_option(example: str) -> Any:
    """``--set KEY=VALUE``, repeatable, merged into the template before validation."""
    return click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
                        help=f"Override a template field before validation, e.g. --set {example} (repeatable).")


#: the override ``--figures`` stands for
FIGURES_OVERRIDE = "output.figures=true"


def figures_option(func: Callable[..., Any]) -> Callable[..., Any]:
    """``--figures``: also write the PNG and SVG figures (``--set output.figures=true``); the command's function
    receives it as one more of its ``overrides``."""
    @functools.wraps(func)
    def wrapper(*args: Any, figures: bool = False, **kwargs: Any) -> Any:
        if figures:
            kwargs["overrides"] = (*kwargs.get("overrides", ()), FIGURES_OVERRIDE)
        return func(*args, **kwargs)
    return click.option("--figures", is_flag=True, help="Also write the figures as PNG and SVG (off by default: the "
                        "page plots the same curves; same as --set output.figures=true).")(wrapper)


#: room (bytes) a path given for an output folder must leave for the names of the files written in it (a name of
#: up to 100 characters, a suffix such as ``-kit-assembly.dxf`` and a temporary's ``.<name>.<pid>.tmp``)
FILE_NAME_ROOM = 160


def too_long(path: Path) -> str | None:
    """Why the file system cannot hold ``path`` (a name in it longer than the file system's limit, or the whole path
    longer than its limit less :data:`FILE_NAME_ROOM`), or None; the limits are those of the nearest folder of the
    path that exists (255 and 4096 bytes where the system does not say)."""
    base = next((p for p in (path.absolute(), *path.absolute().parents) if _exists(p)), Path(path.anchor or "."))
    name_max, path_max = (_limit(base, key, default) for key, default in (("PC_NAME_MAX", 255), ("PC_PATH_MAX", 4096)))
    for part in path.parts:
        if len(os.fsencode(part)) > name_max:
            return (f"a name of {len(os.fsencode(part))} bytes ({part[:24]}...) is longer than the file system allows "
                    f"({name_max})")
    size = len(os.fsencode(str(path.absolute())))
    if size > path_max - FILE_NAME_ROOM:
        return (f"the path is {size} bytes long: the file system allows {path_max}, less {FILE_NAME_ROOM} for the "
                "names of the files in it")
    return None


def _exists(path: Path) -> bool:
    """Whether ``path`` exists; False for a path the system cannot even look up (a name too long)."""
    try:
        return path.exists() or path.is_symlink()
    except OSError:
        return False


def _limit(folder: Path, key: str, default: int) -> int:
    try:
        return int(os.pathconf(folder, key))
    except (OSError, ValueError, AttributeError):       # no such limit here, or no pathconf (Windows)
        return default


def _output_folder(ctx: click.Context, param: click.Parameter, value: Path | None) -> Path | None:
    """Check ``-o`` before any work: a folder, or one that can be made (no file where a folder must be, no name
    longer than the file system allows)."""
    if value is None:
        return value
    why = too_long(value)
    if why is not None:
        raise click.BadParameter(f"cannot create output folder: {why}", ctx, param)
    for folder in (value, *value.parents):
        if _exists(folder):
            if not folder.is_dir():
                raise click.BadParameter(f"cannot create output folder {value}: Not a directory ({folder} is a file)",
                                         ctx, param)
            if not os.access(folder, os.W_OK | os.X_OK):
                raise click.BadParameter(f"cannot create output folder {value}: {folder} is not writable", ctx,
                                         param)
            break
    return value


def output_option(help: str, **kwargs: Any) -> Any:
    """``-o/--output``: a folder, checked before any work (see :func:`_output_folder`)."""
    return click.option("-o", "--output", type=click.Path(file_okay=False, path_type=Path), callback=_output_folder,
                        help=help, **kwargs)


def template_options(example: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """TEMPLATE, ``-o/--output`` (default out/<name>/), ``--set`` (``example`` shows one) and ``--figures``."""
    return lambda func: _apply(func, (
        template_argument(),
        output_option("Output folder (default: out/<name>/).", default=None),
        set_option(example),
        figures_option))


def family_options(func: Callable[..., Any]) -> Callable[..., Any]:
    """The options every ``family`` command takes."""
    return _apply(func, (
        template_argument(),
        output_option("Folder of the family: one sub-folder a member, summary.csv, summary.json, overview.png.",
                      required=True),
        click.option("--jobs", type=click.IntRange(1, 256), default=1, show_default=True,
                     help="Processes to build with."),
        click.option("--scheduler", metavar="ADDRESS", default=None,
                     help="Build on the Dask cluster at ADDRESS (e.g. tcp://host:8786) instead of local "
                          "processes.")))


@dataclass(frozen=True)
class Family:
    """What a product's ``family`` command calls: ``validate`` (raw template -> spec), ``build_member`` (raw
    template, folder -> summary row; a module-level function, so that worker processes and Dask can take it) and
    ``nestable`` (spec -> why a family's ``[sheet]`` cannot nest the member's cut part, or None; None itself: the
    product's families take no ``[sheet]``) and ``thumbnail_bore`` (spec -> the bore, mm, the overview draws about
    the centre of the member's thumbnail; None: none drawn)."""

    validate: Callable[[dict[str, Any]], Any]
    build_member: Callable[[dict[str, Any], Path], dict[str, Any]]
    nestable: Callable[[Any], str | None] | None = None
    thumbnail_bore: Callable[[Any], float] | None = None


@dataclass(frozen=True)
class Starters:
    """What a product's ``new`` command offers: ``what`` (each starter's name -> what it is, its first line listed)
    and ``text`` (name, template name -> the starter's TOML text; a :class:`SpecError` naming ``KIND`` for a name
    that is none)."""

    what: Mapping[str, str]
    text: Callable[[str, str], str]


def add_family(group: click.Group, family: Callable[[], Family], what: str) -> None:
    """Give ``group`` a ``family TEMPLATE -o DIR [--jobs N] [--scheduler ADDRESS]`` command calling what
    ``family()`` gives (called, and so its modules imported, only when the command runs); ``what`` is its help."""
    @group.command(name="family", help=what)
    @family_options
    @user_errors
    def family_command(template: Path, output: Path, jobs: int, scheduler: str | None) -> None:
        from camgen.core.family import build_family

        calls = family()
        report_family(build_family(template, output, calls.validate, calls.build_member, jobs, scheduler,
                                   calls.nestable, calls.thumbnail_bore), output)


def add_bench(group: click.Group, run: Callable[[], Callable[[Path, bool], dict[str, Any]]], default: Path,
              what: str) -> None:
    """Give ``group`` a ``bench [--quick] [-o DIR]`` command running ``run()(folder, quick)`` (``run`` imports the
    bench only when the command runs); ``what`` is its help."""
    @group.command(name="bench", help=what)
    @click.option("--quick", is_flag=True, help="Fewer tolerances, sizes and repeats.")
    @output_option("Folder for RESULTS.md, results.json and any plots.", default=default, show_default=True)
    @user_errors
    def bench(quick: bool, output: Path) -> None:
        results = run()(output, quick)
        wrong = [c for c in results["hard_cases"] if c["outcome"].startswith("WRONG")]
        for name in sorted(p.name for p in output.iterdir()):
            click.echo(f"wrote {output / name}")
        click.echo(f"{len(results['hard_cases'])} hard cases, {len(wrong)} wrong")


def add_new(group: click.Group, starters: Callable[[], Starters], program: str) -> None:
    """Give ``group`` a ``new [NAME] [-o FILE] [--example]`` command: NAME is a starter of ``starters()`` (called only
    when the command runs), whose template it writes, or one of ``program``'s bundled examples
    (:mod:`camgen.core.examples`), which it copies with the files it reads; ``--example`` picks the example where a
    starter has the same name. Without NAME it lists the starters. An existing file is never overwritten."""
    @group.command(name="new", help=f"Write a commented starter template of the kind NAME, or a copy of the bundled "
                                    f"example NAME (`{program} examples` lists them), that `{program}` takes as it "
                                    "is (without NAME: list the kinds).")
    @click.argument("kind", metavar="NAME", required=False)
    @click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path), default=None,
                  help="The template to write (default: NAME.toml here); its name is the file's.")
    @click.option("--example", is_flag=True,
                  help="Copy the bundled example NAME, where a kind has the same name (plate, grooved, ...).")
    @one_design
    def new(kind: str | None, output: Path | None, example: bool) -> None:
        import re

        from camgen.core.errors import SpecError
        from camgen.core.spec import NAME_PATTERN

        offered = starters()
        if kind is None:
            for name, what in offered.what.items():
                click.echo(f"{name:<20} {what.splitlines()[0]}")
            return
        path = output if output is not None else Path(f"{kind}.toml")
        why = too_long(path)
        if why is not None:
            raise SpecError(f"cannot write {path.name[:24]}: {why}", "--output")
        if not re.match(NAME_PATTERN, path.stem):
            raise SpecError(f"{path.stem!r} cannot name a template: letters, digits, '.', '_' and '-'", "--output")
        if example or kind not in offered.what:
            bundled = _example(kind, program, example)
            if bundled is not None:
                _write_example(bundled, path)
                return
        try:
            text = offered.text(kind, path.stem)
        except SpecError as exc:
            raise _not_a_kind(exc, kind, program) from None
        if not path.parent.is_dir():
            raise SpecError(f"no folder {path.parent}", "--output")
        _write_new(path, text.encode("utf-8"))
        click.echo(f"wrote {path}")


def _example(name: str, program: str, asked: bool) -> Any:
    """The bundled example ``name`` of ``program``; None where there is none and none was ``asked`` for (``name`` may
    be a kind); a one-line :class:`SpecError` on NAME for an example of the other program, or an unknown one asked
    for."""
    from camgen.core.errors import SpecError
    from camgen.core.examples import examples
    from camgen.core.options import choose

    bundled = examples()
    found = bundled.get(name)
    if found is not None and found.program != program:
        raise SpecError(f"{name!r} is a {found.program} example: {found.program} new {name}", "NAME")
    if found is None and asked:
        choose(name, [e.name for e in bundled.values() if e.program == program], "NAME")
    return found


def _not_a_kind(error: Any, name: str, program: str) -> Any:
    """``error`` (an unknown kind) told that NAME may also be an example, naming the closest of ``program``'s."""
    import difflib

    from camgen.core.errors import SpecError
    from camgen.core.examples import examples

    near = difflib.get_close_matches(name, list(examples(program)), n=1)
    hint = f" (did you mean the example {near[0]!r}?)" if near else ""
    return SpecError(f"{error.detail}; or an example{hint}: `{program} examples` lists them", error.field)


def _write_example(example: Any, path: Path) -> None:
    """Copy ``example`` to ``path`` with the files it reads (:func:`camgen.core.examples.copy_plan`), all checked
    before any is written, and print each file written."""
    from camgen.core.errors import SpecError
    from camgen.core.examples import copy_plan

    if not path.parent.is_dir():
        raise SpecError(f"no folder {path.parent}", "--output")
    plan = copy_plan(example, path)
    for destination, _ in plan[1:]:
        if not destination.parent.is_dir():
            raise SpecError(f"no folder {destination.parent} for {destination.name}, which {path.name} reads",
                            "--output")
    for destination, content in plan:
        _write_new(destination, content)
        click.echo(f"wrote {destination}")
    click.echo(f"run it with:  {example.run_line(str(path))}")


def _write_new(path: Path, content: bytes) -> None:
    """Write ``content`` to the new file ``path`` through a temporary file linked into place, so that a file that
    appeared meanwhile is never overwritten (a one-line :class:`SpecError` on ``--output`` then)."""
    from camgen.core.errors import SpecError

    if path.exists():
        raise SpecError(f"{path} exists; give another file", "--output")
    temp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    temp.write_bytes(content)
    try:
        os.link(temp, path)                              # fails if the file appeared meanwhile: never overwrites
    except FileExistsError:
        raise SpecError(f"{path} exists; give another file", "--output") from None
    finally:
        temp.unlink()


def add_examples(group: click.Group, program: str) -> None:
    """Give ``group`` an ``examples`` command listing ``program``'s bundled templates, one line each."""
    @group.command(name="examples", help=f"List the bundled example templates `{program} new NAME` copies, one line "
                                         "each: the name, the command that runs it, what it is.")
    @one_design
    def examples_command() -> None:
        from camgen.core.examples import examples

        for example in examples(program).values():
            click.echo(f"{example.name:<20} {example.command:<11} {example.summary}")


def report_family(rows: list[dict], output: Path) -> None:
    """Print a family run's outcome: counts, where the summary is, and each failure with its reason."""
    fresh = [r for r in rows if not r.get("reused")]
    built = sum(r["status"] == "ok" for r in fresh)
    reused = len(rows) - len(fresh)
    before = sum(r["status"] != "ok" for r in rows if r.get("reused"))
    counts = [f"{built} built"] + ([f"{len(fresh) - built} failed"] if fresh else [])
    if reused:
        counts.append(f"{reused} already there" + (f" ({before} of them failed)" if before else ""))
    click.echo(f"{len(rows)} members: {', '.join(counts)}; summary in {output / 'summary.csv'}")
    for r in rows:
        if r["status"] != "ok":
            click.echo(f"failed {r['name']}: {r['error']}")


def animation_options(func: Callable[..., Any]) -> Callable[..., Any]:
    """The options of an ``animate`` command: TEMPLATE, ``-o``, ``--set``, ``--frames``, ``--size``, ``--format``,
    ``--fps``; the function receives them checked, as one :class:`~camgen.core.animation.AnimationOptions`
    ``options`` (a bad value: one line naming its option, before any work)."""
    from camgen.core.animation import DEFAULT_FPS, DEFAULT_FRAMES, DEFAULT_SIZE, FORMATS, FPS, FRAMES, PIXELS

    @functools.wraps(func)
    def wrapper(*args: Any, frames: int, size: str, fmt: str, fps: float, **kwargs: Any) -> Any:
        from camgen.core.animation import animation_options as checked

        return func(*args, options=user_errors(checked)(frames, size, fps, fmt), **kwargs)

    return _apply(wrapper, (
        template_argument(),
        output_option("Folder for the animation (default: out/<name>/).", default=None),
        set_option("name=demo"),
        click.option("--frames", type=int, default=DEFAULT_FRAMES, show_default=True,
                     help=f"Frames in the cycle ({FRAMES[0]} to {FRAMES[1]})."),
        click.option("--size", default="{}x{}".format(*DEFAULT_SIZE), show_default=True, metavar="WxH",
                     help=f"Frame size in pixels, each side even, {PIXELS[0]} to {PIXELS[1]}."),
        click.option("--format", "fmt", type=click.Choice(FORMATS), default="gif", show_default=True,
                     help="gif (Pillow), or mp4 / webm (imageio-ffmpeg: the anim extra)."),
        click.option("--fps", type=float, default=DEFAULT_FPS, show_default=True,
                     help=f"Frames per second ({FPS[0]:g} to {FPS[1]:g})."),
    ))


def write_animation_file(frames: Any, options: Any, directory: Path, name: str) -> Path:
    """Write ``frames`` as ``directory/<name>-animation.<format>`` (the folder made if missing, and removed again if
    the writing fails) and return the path."""
    from camgen.core.writers.animation import write_animation

    made = [p for p in (directory, *directory.parents) if not _exists(p)]
    directory.mkdir(parents=True, exist_ok=True)
    path = directory / f"{name}-animation.{options.format}"
    try:
        write_animation(frames, path, options.format, options.fps)
    except BaseException:
        for folder in made:
            with contextlib.suppress(OSError):
                folder.rmdir()
        raise
    return path
