"""Scenario files: the table, the camera, the objects and a timeline of events.

The format is documented in ``scenarios/SCHEMA.md``. :func:`load_scenario` reads a YAML file,
keeps the line of every mapping so that every error names file, line and cause, and validates
everything it can before a frame is rendered (unknown categories, shapes and objects, events
out of order, NaN, overlapping objects at the start, objects that do not fit under their
container).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from probanchor.tabletop.colours import COLOUR_ALIASES, NAMED_COLOURS, TABLE_RGB
from probanchor.tabletop.errors import ScenarioError

# category -> default shape. A scenario may give another shape explicitly.
CATEGORY_SHAPES: dict[str, str] = {
    "ball": "sphere",
    "mug": "mug",
    "cup": "cup",
    "box": "box",
    "block": "box",
    "can": "cylinder",
    "bottle": "cylinder",
    "bowl": "cup",
}
SHAPES = ("sphere", "cylinder", "cup", "mug", "box", "mesh")
CONTAINER_SHAPES = ("cup", "mug", "box", "mesh")
EVENT_KINDS = (
    "move",
    "pick_up",
    "put_down",
    "put_under",
    "lift",
    "swap",
    "shuffle",
    "cover_camera",
    "remove",
)
WALL = 0.004  # wall thickness of cups, mugs and containers (m)
HANDLE = 0.025  # how far a mug's handle sticks out (m); a mug's origin is its box centre
MAX_FPS = 240.0  # frames per second a scenario may ask for (more only multiplies frames)
MAX_IMAGE_SIDE = 4096  # pixels, the camera image's width and height at most


@dataclass
class CameraSpec:
    """A pinhole camera looking from ``position`` at ``target`` (world frame, metres, z up).

    Intrinsics are either ``fov_y`` (degrees, principal point at the image centre) or explicit
    ``fx, fy, cx, cy`` in pixels for ``width x height``; they scale with the rendered size.
    Depth outside ``[min_depth, max_depth]`` is reported as 0 (no return), as a Kinect does.
    """

    width: int = 320
    height: int = 240
    fov_y: float = 45.0
    fx: float | None = None
    fy: float | None = None
    cx: float | None = None
    cy: float | None = None
    position: tuple[float, float, float] = (0.0, -0.5, 0.87)
    target: tuple[float, float, float] = (0.0, 0.05, 0.0)
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)
    near: float = 0.02
    far: float = 3.0
    min_depth: float = 0.25
    max_depth: float = 2.5

    def intrinsics(self, width: int, height: int) -> tuple[float, float, float, float]:
        """(fx, fy, cx, cy) in pixels for an image of ``width x height``."""
        sx, sy = width / self.width, height / self.height
        if self.fx is not None:
            fx = self.fx * sx
            fy = (self.fy if self.fy is not None else self.fx) * sy
            cx = (self.cx if self.cx is not None else self.width / 2 - 0.5) * sx
            cy = (self.cy if self.cy is not None else self.height / 2 - 0.5) * sy
            return fx, fy, cx, cy
        fy = (height / 2) / math.tan(math.radians(self.fov_y) / 2)
        return fy, fy, width / 2 - 0.5, height / 2 - 0.5


@dataclass
class NoiseSpec:
    """Sensor noise: depth sigma = ``depth_sigma_base + depth_sigma_quadratic * z**2`` (m);
    pixels next to a depth jump larger than ``edge_jump`` lose their depth with probability
    ``edge_dropout``; RGB gets Gaussian noise of ``colour_sigma`` levels."""

    enabled: bool = True
    depth_sigma_base: float = 0.0005
    depth_sigma_quadratic: float = 0.001
    edge_jump: float = 0.03
    edge_dropout: float = 0.5
    colour_sigma: float = 3.0


@dataclass
class ObjectSpec:
    """One object. Positions are the centre of the object (metres, world frame)."""

    id: str
    category: str
    shape: str
    colour: tuple[float, float, float]
    colour_name: str | None = None
    radius: float = 0.03
    height: float = 0.06
    size: tuple[float, float, float] = (0.06, 0.06, 0.06)
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)
    yaw: float = 0.0  # degrees
    upside_down: bool = False
    under: str | None = None
    mesh: str | None = None
    mesh_scale: float = 1.0
    line: int | None = None

    def half_extents(self) -> tuple[float, float, float]:
        """Half extents of the axis-aligned box (in the object's own frame)."""
        if self.shape == "sphere":
            return (self.radius, self.radius, self.radius)
        if self.shape in ("cylinder", "cup"):
            r = self.radius * (1.2 if self.shape == "cup" else 1.0)
            return (r, r, self.height / 2)
        if self.shape == "mug":
            return (self.radius + HANDLE / 2, self.radius, self.height / 2)
        return (self.size[0] / 2, self.size[1] / 2, self.size[2] / 2)

    def world_extents(self) -> tuple[float, float, float]:
        """Extents of the world-frame axis-aligned bounding box at the object's yaw."""
        hx, hy, hz = self.half_extents()
        a = math.radians(self.yaw)
        c, s = abs(math.cos(a)), abs(math.sin(a))
        if self.shape in ("sphere", "cylinder", "cup"):
            return (2 * hx, 2 * hy, 2 * hz)
        if self.shape == "mug":  # a round tube (off-centre) and a handle pointing along yaw
            ca, sa = math.cos(a), math.sin(a)
            tube = (-HANDLE / 2 * ca, -HANDLE / 2 * sa)
            tip = (tube[0] + (self.radius + HANDLE) * ca, tube[1] + (self.radius + HANDLE) * sa)
            ex = max(tube[0] + self.radius, tip[0]) - min(tube[0] - self.radius, tip[0])
            ey = max(tube[1] + self.radius, tip[1]) - min(tube[1] - self.radius, tip[1])
            return (ex, ey, 2 * hz)
        return (2 * (c * hx + s * hy), 2 * (s * hx + c * hy), 2 * hz)

    @property
    def rest_z(self) -> float:
        """z of the centre when the object stands on the table."""
        return self.half_extents()[2]

    def footprint_radius(self) -> float:
        hx, hy, _ = self.half_extents()
        if self.shape in ("sphere", "cylinder", "cup"):
            return hx
        return math.hypot(hx, hy)

    def cavity_offset(self) -> tuple[float, float]:
        """World (dx, dy) from the body's origin to the centre of its cavity (a mug's origin
        is the centre of its bounding box, handle included, so its tube sits off-centre)."""
        if self.shape != "mug":
            return (0.0, 0.0)
        a = math.radians(self.yaw)
        return (-HANDLE / 2 * math.cos(a), -HANDLE / 2 * math.sin(a))

    def inner_radius(self) -> float:
        """Radius of the largest upright cylinder that fits under this container."""
        if self.shape in ("cup", "mug"):
            return self.radius - WALL
        hx, hy, _ = self.half_extents()
        return min(hx, hy) - WALL

    def inner_height(self) -> float:
        return 2 * self.half_extents()[2] - WALL

    @property
    def is_container(self) -> bool:
        return self.shape in CONTAINER_SHAPES


@dataclass
class Event:
    """One timeline entry: ``kind`` at time ``at`` with its parameters (see SCHEMA.md)."""

    at: float
    kind: str
    params: dict[str, Any] = field(default_factory=dict)
    line: int | None = None


@dataclass
class Scenario:
    name: str
    objects: list[ObjectSpec]
    events: list[Event] = field(default_factory=list)
    camera: CameraSpec = field(default_factory=CameraSpec)
    noise: NoiseSpec = field(default_factory=NoiseSpec)
    fps: float = 15.0
    duration: float | None = None
    table_size: tuple[float, float] = (1.0, 0.8)
    table_colour: tuple[float, float, float] = TABLE_RGB
    hand_size: tuple[float, float, float] = (0.10, 0.09, 0.07)
    source: str | None = None

    def object(self, oid: str) -> ObjectSpec:
        for obj in self.objects:
            if obj.id == oid:
                return obj
        raise KeyError(oid)

    @property
    def object_ids(self) -> list[str]:
        return [o.id for o in self.objects]

    def end_time(self) -> float:
        """Scenario length: ``duration`` or one second after the last event ends."""
        if self.duration is not None:
            return self.duration
        end = 0.0
        for ev in self.events:
            end = max(end, ev.at + float(ev.params.get("duration", 2.0)))
        return end + 1.0

    def validate(self) -> None:
        validate_scenario(self)


# --------------------------------------------------------------------------------------------
# YAML with line numbers


class _LDict(dict):
    line: int | None = None
    key_lines: dict[str, int]


class _LList(list):
    line: int | None = None


class _LineLoader(yaml.SafeLoader):
    pass


def _construct_mapping(loader: _LineLoader, node: yaml.MappingNode) -> _LDict:
    loader.flatten_mapping(node)
    out = _LDict()
    out.line = node.start_mark.line + 1
    out.key_lines = {}
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        out[key] = loader.construct_object(value_node, deep=True)
        out.key_lines[str(key)] = key_node.start_mark.line + 1
    return out


def _construct_sequence(loader: _LineLoader, node: yaml.SequenceNode) -> _LList:
    out = _LList(loader.construct_object(child, deep=True) for child in node.value)
    out.line = node.start_mark.line + 1
    return out


_LineLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)
_LineLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_SEQUENCE_TAG, _construct_sequence)
# YAML 1.1 would read .nan as NaN silently; keep it, and catch NaN in validation.


def _line(node: Any, key: str | None = None) -> int | None:
    if isinstance(node, _LDict):
        if key is not None and key in node.key_lines:
            return node.key_lines[key]
        return node.line
    return getattr(node, "line", None)


class _Reader:
    """Typed access to a parsed mapping, raising ScenarioError with file and line."""

    def __init__(self, source: str, node: Any, what: str) -> None:
        if not isinstance(node, dict):
            raise ScenarioError(f"{what} must be a mapping, got {type(node).__name__}", source,
                                _line(node))
        self.source, self.node, self.what = source, node, what

    def fail(self, cause: str, key: str | None = None) -> ScenarioError:
        return ScenarioError(f"{self.what}: {cause}", self.source, _line(self.node, key))

    def has(self, key: str) -> bool:
        return key in self.node

    def number(self, key: str, default: float | None = None, positive: bool = False,
               at_most: float | None = None) -> float:
        if key not in self.node:
            if default is None:
                raise self.fail(f"missing '{key}'")
            return default
        value = self.node[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.fail(f"'{key}' must be a number, got {value!r}", key)
        if not math.isfinite(value):
            raise self.fail(f"'{key}' is {value} (NaN or infinite)", key)
        if positive and value <= 0:
            raise self.fail(f"'{key}' must be positive, got {value}", key)
        if at_most is not None and value > at_most:
            raise self.fail(f"'{key}' must be at most {at_most:g}, got {value}", key)
        return float(value)

    def vector(self, key: str, lengths: tuple[int, ...], default: Any = None) -> tuple[float, ...]:
        if key not in self.node:
            if default is None:
                raise self.fail(f"missing '{key}'")
            return tuple(default)
        return _vector(self.node[key], lengths, self.fail, key)

    def string(self, key: str, default: str | None = None) -> str:
        if key not in self.node:
            if default is None:
                raise self.fail(f"missing '{key}'")
            return default
        value = self.node[key]
        if not isinstance(value, str):
            raise self.fail(f"'{key}' must be a string, got {value!r}", key)
        return value

    def boolean(self, key: str, default: bool) -> bool:
        value = self.node.get(key, default)
        if not isinstance(value, bool):
            raise self.fail(f"'{key}' must be true or false, got {value!r}", key)
        return value

    def unknown_keys(self, allowed: set[str]) -> None:
        for key in self.node:
            if key not in allowed:
                raise self.fail(f"unknown key '{key}' (allowed: {', '.join(sorted(allowed))})",
                                str(key))


def _vector(value: Any, lengths: tuple[int, ...], fail: Any, key: str) -> tuple[float, ...]:
    if not isinstance(value, (list, tuple)) or len(value) not in lengths:
        want = " or ".join(str(n) for n in lengths)
        raise fail(f"'{key}' must be a list of {want} numbers, got {value!r}", key)
    out = []
    for v in value:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise fail(f"'{key}' must contain numbers, got {v!r}", key)
        if not math.isfinite(v):
            raise fail(f"'{key}' contains {v} (NaN or infinite)", key)
        out.append(float(v))
    return tuple(out)


def _colour(r: _Reader, key: str = "colour") -> tuple[tuple[float, float, float], str | None]:
    if not r.has(key):
        raise r.fail(f"missing '{key}' (a name or [r, g, b] in 0..1)")
    value = r.node[key]
    if isinstance(value, str):
        value = COLOUR_ALIASES.get(value, value)
        if value not in NAMED_COLOURS:
            raise r.fail(f"unknown colour '{value}' (known: {', '.join(NAMED_COLOURS)})", key)
        return NAMED_COLOURS[value], value
    rgb = _vector(value, (3,), r.fail, key)
    if any(c < 0 or c > 1 for c in rgb):
        raise r.fail(f"'{key}' components must be in 0..1, got {list(rgb)}", key)
    return (rgb[0], rgb[1], rgb[2]), None


# --------------------------------------------------------------------------------------------
# parsing

_OBJECT_KEYS = {"id", "category", "shape", "colour", "color", "radius", "height", "size",
                "position", "yaw", "upside_down", "under", "mesh", "mesh_scale"}
_EVENT_KEYS = {"at", "do", "object", "to", "via", "speed", "duration", "container", "a", "b",
               "containers", "order", "hand", "height", "move"}
_CAMERA_KEYS = {"width", "height", "fov_y", "fx", "fy", "cx", "cy", "position", "target", "up",
                "near", "far", "min_depth", "max_depth"}
_NOISE_KEYS = {"depth_sigma_base", "depth_sigma_quadratic", "edge_jump", "edge_dropout",
               "colour_sigma"}
_TOP_KEYS = {"name", "fps", "duration", "camera", "noise", "table", "objects", "events",
             "hand_size"}


def _parse_object(source: str, node: Any, base_dir: Path) -> ObjectSpec:
    r = _Reader(source, node, "object")
    r.unknown_keys(_OBJECT_KEYS)
    oid = r.string("id")
    r.what = f"object '{oid}'"
    category = r.string("category")
    if category not in CATEGORY_SHAPES:
        raise r.fail(f"unknown category '{category}' (known: {', '.join(CATEGORY_SHAPES)})",
                     "category")
    shape = r.string("shape", CATEGORY_SHAPES[category])
    if shape not in SHAPES:
        raise r.fail(f"unknown shape '{shape}' (known: {', '.join(SHAPES)})", "shape")
    key = "colour" if r.has("colour") or not r.has("color") else "color"
    colour, colour_name = _colour(r, key)
    obj = ObjectSpec(id=oid, category=category, shape=shape, colour=colour,
                     colour_name=colour_name, line=_line(node))
    if shape == "sphere":
        obj.radius = r.number("radius", 0.03, positive=True)
    elif shape in ("cylinder", "cup", "mug"):
        obj.radius = r.number("radius", 0.04, positive=True)
        obj.height = r.number("height", 0.1, positive=True)
    else:
        size = r.vector("size", (3,), (0.06, 0.06, 0.06))
        if any(s <= 0 for s in size):
            raise r.fail(f"'size' must be positive, got {list(size)}", "size")
        obj.size = (size[0], size[1], size[2])
    if shape == "mesh":
        mesh = Path(r.string("mesh"))
        if not mesh.is_absolute():
            mesh = base_dir / mesh
        if not mesh.exists():
            raise r.fail(f"mesh file {mesh} does not exist", "mesh")
        obj.mesh = str(mesh)
        obj.mesh_scale = r.number("mesh_scale", 1.0, positive=True)
    obj.yaw = r.number("yaw", 0.0)
    obj.upside_down = r.boolean("upside_down", shape in ("cup", "mug"))
    obj.under = r.string("under") if r.has("under") else None
    if obj.under is None:
        pos = r.vector("position", (2, 3))
        z = pos[2] if len(pos) == 3 else obj.rest_z
        obj.position = (pos[0], pos[1], z)
    elif r.has("position"):
        raise r.fail("an object 'under' a container takes the container's position; "
                     "remove 'position'", "position")
    return obj


def _parse_event(source: str, node: Any) -> Event:
    r = _Reader(source, node, "event")
    r.unknown_keys(_EVENT_KEYS)
    at = r.number("at")
    if at < 0:
        raise r.fail(f"'at' must be >= 0, got {at}", "at")
    kind = r.string("do")
    if kind not in EVENT_KINDS:
        raise r.fail(f"unknown event '{kind}' (known: {', '.join(EVENT_KINDS)})", "do")
    r.what = f"event '{kind}' at {at}"
    params: dict[str, Any] = {}
    for key in ("object", "container", "a", "b", "hand", "move"):
        if r.has(key):
            params[key] = r.string(key)
    for key in ("speed", "duration", "height"):
        if r.has(key):
            params[key] = r.number(key, positive=True)
    if r.has("to"):
        params["to"] = r.vector("to", (2, 3))
    if r.has("via"):
        via = node["via"]
        if not isinstance(via, list):
            raise r.fail("'via' must be a list of points", "via")
        params["via"] = [_vector(v, (2, 3), r.fail, "via") for v in via]
    for key in ("containers", "order"):
        if r.has(key):
            value = node[key]
            if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
                raise r.fail(f"'{key}' must be a list of object ids", key)
            params[key] = list(value)
    return Event(at=at, kind=kind, params=params, line=_line(node))


def parse_scenario(data: Any, source: str = "<scenario>", base_dir: Path | None = None
                   ) -> Scenario:
    """Build and validate a :class:`Scenario` from parsed YAML (a mapping)."""
    base = base_dir or Path(".")
    top = _Reader(source, data, "scenario")
    top.unknown_keys(_TOP_KEYS)
    name = top.string("name", Path(source).stem)
    camera = CameraSpec()
    if top.has("camera"):
        c = _Reader(source, data["camera"], "camera")
        c.unknown_keys(_CAMERA_KEYS)
        camera.width = int(c.number("width", camera.width, positive=True, at_most=MAX_IMAGE_SIDE))
        camera.height = int(c.number("height", camera.height, positive=True,
                                     at_most=MAX_IMAGE_SIDE))
        camera.fov_y = c.number("fov_y", camera.fov_y, positive=True)
        for key in ("fx", "fy", "cx", "cy"):
            if c.has(key):
                setattr(camera, key, c.number(key, positive=True))
        camera.position = c.vector("position", (3,), camera.position)  # type: ignore[assignment]
        camera.target = c.vector("target", (3,), camera.target)  # type: ignore[assignment]
        camera.up = c.vector("up", (3,), camera.up)  # type: ignore[assignment]
        for key in ("near", "far", "min_depth", "max_depth"):
            setattr(camera, key, c.number(key, getattr(camera, key), positive=True))
        if camera.position == camera.target:
            raise c.fail("camera position equals its target", "target")
        view = [t - p for t, p in zip(camera.target, camera.position, strict=True)]
        cross = (view[1] * camera.up[2] - view[2] * camera.up[1],
                 view[2] * camera.up[0] - view[0] * camera.up[2],
                 view[0] * camera.up[1] - view[1] * camera.up[0])
        if math.hypot(*cross) <= 1e-9 * math.hypot(*view) * max(math.hypot(*camera.up), 1e-300):
            raise c.fail("the camera looks along its 'up' vector (no image orientation)", "up")
    noise = NoiseSpec()
    if top.has("noise"):
        if data["noise"] is False:
            noise.enabled = False
        else:
            n = _Reader(source, data["noise"], "noise")
            n.unknown_keys(_NOISE_KEYS)
            for key in _NOISE_KEYS:
                setattr(noise, key, n.number(key, getattr(noise, key)))
    table_size: tuple[float, float] = (1.0, 0.8)
    table_colour = TABLE_RGB
    if top.has("table"):
        t = _Reader(source, data["table"], "table")
        t.unknown_keys({"size", "colour"})
        ts = t.vector("size", (2,), table_size)
        table_size = (ts[0], ts[1])
        if t.has("colour"):
            table_colour, _ = _colour(t)
    if not top.has("objects") or not isinstance(data["objects"], list):
        raise top.fail("missing 'objects' (a list)", "objects")
    objects = [_parse_object(source, o, base) for o in data["objects"]]
    events_node = data.get("events", []) or []
    if not isinstance(events_node, list):
        raise top.fail("'events' must be a list", "events")
    events = [_parse_event(source, e) for e in events_node]
    scenario = Scenario(
        name=name,
        objects=objects,
        events=events,
        camera=camera,
        noise=noise,
        fps=top.number("fps", 15.0, positive=True, at_most=MAX_FPS),
        duration=top.number("duration", positive=True) if top.has("duration") else None,
        table_size=table_size,
        table_colour=table_colour,
        source=source,
    )
    if top.has("hand_size"):
        hs = top.vector("hand_size", (3,))
        scenario.hand_size = (hs[0], hs[1], hs[2])
    validate_scenario(scenario)
    return scenario


def load_scenario(path: str | Path) -> Scenario:
    """Read and validate a scenario file; errors name the file, the line and the cause."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ScenarioError(f"cannot read: {exc.strerror}", str(path)) from exc
    except UnicodeDecodeError as exc:
        line = path.read_bytes()[:exc.start].count(b"\n") + 1
        raise ScenarioError(f"not UTF-8 text: byte {exc.object[exc.start]:#04x}", str(path),
                            line) from exc
    try:
        data = yaml.load(text, Loader=_LineLoader)  # noqa: S506 - a SafeLoader subclass
    except yaml.MarkedYAMLError as exc:
        line = exc.problem_mark.line + 1 if exc.problem_mark else None
        raise ScenarioError(f"not valid YAML: {exc.problem}", str(path), line) from exc
    except RecursionError as exc:
        raise ScenarioError("nested too deeply to be a scenario", str(path)) from exc
    try:
        return parse_scenario(data, str(path), path.parent)
    except RecursionError as exc:
        raise ScenarioError("nested too deeply to be a scenario", str(path)) from exc


# --------------------------------------------------------------------------------------------
# validation


def _err(scn: Scenario, cause: str, line: int | None) -> ScenarioError:
    return ScenarioError(cause, scn.source, line)


def validate_scenario(scn: Scenario) -> None:
    """Raise :class:`ScenarioError` for the first inconsistency found."""
    ids: dict[str, ObjectSpec] = {}
    for obj in scn.objects:
        if obj.category not in CATEGORY_SHAPES:
            raise _err(scn, f"object '{obj.id}': unknown category '{obj.category}'", obj.line)
        if obj.shape not in SHAPES:
            raise _err(scn, f"object '{obj.id}': unknown shape '{obj.shape}'", obj.line)
        if obj.id in ids:
            raise _err(scn, f"object id '{obj.id}' is used twice", obj.line)
        if obj.id.startswith("hand"):
            raise _err(scn, f"object id '{obj.id}': ids starting with 'hand' are reserved",
                       obj.line)
        for v in (*obj.position, obj.yaw, obj.radius, obj.height, *obj.size):
            if not math.isfinite(v):
                raise _err(scn, f"object '{obj.id}': NaN or infinity in its pose or size",
                           obj.line)
        ids[obj.id] = obj
    # containment at the start: resolve 'under' chains (innermost first)
    for obj in scn.objects:
        if obj.under is None:
            continue
        if obj.under not in ids:
            raise _err(scn, f"object '{obj.id}' is under unknown object '{obj.under}'",
                       obj.line)
        _check_fits(scn, obj, ids[obj.under], obj.line)
    seen: set[str] = set()
    for obj in scn.objects:
        chain, cur = [obj.id], obj
        while cur.under is not None:
            cur = ids[cur.under]
            if cur.id in chain:
                raise _err(scn, f"object '{obj.id}': circular 'under' chain", obj.line)
            chain.append(cur.id)
        seen.add(obj.id)
    def place(obj: ObjectSpec) -> tuple[float, float, float]:
        if obj.under is None:
            return obj.position
        outer = ids[obj.under]
        ox, oy, _ = place(outer)
        dx, dy = outer.cavity_offset()
        return (ox + dx, oy + dy, obj.rest_z)

    for obj in scn.objects:
        obj.position = place(obj)
    # overlapping objects at the start (footprints in the table plane)
    free = [o for o in scn.objects if o.under is None]
    for i, a in enumerate(free):
        for b in free[i + 1:]:
            d = math.dist(a.position[:2], b.position[:2])
            za = (a.position[2] - a.half_extents()[2], a.position[2] + a.half_extents()[2])
            zb = (b.position[2] - b.half_extents()[2], b.position[2] + b.half_extents()[2])
            if d < 0.9 * (a.footprint_radius() + b.footprint_radius()) and \
                    za[0] < zb[1] and zb[0] < za[1]:
                raise _err(scn, f"objects '{a.id}' and '{b.id}' overlap at the start "
                           f"({d:.3f} m apart); put one 'under' the other or move it",
                           b.line)
    # the timeline
    last = -math.inf
    busy: dict[str, tuple[float, float, int | None]] = {}
    where = {o.id: (o.position[0], o.position[1]) for o in scn.objects}  # rough, for speeds
    for ev in scn.events:
        if ev.at < last:
            raise _err(scn, f"event '{ev.kind}' at {ev.at} comes after an event at {last}: "
                       "times out of order", ev.line)
        last = ev.at
        for v in ev.params.values():
            if isinstance(v, float) and not math.isfinite(v):
                raise _err(scn, f"event '{ev.kind}': NaN or infinity", ev.line)
        _check_event(scn, ev, ids, where)
        movers = _event_movers(ev)
        end = ev.at + float(ev.params.get("duration", 0.0))
        for m in movers:
            if m in busy and busy[m][1] > ev.at + 1e-9:
                raise _err(scn, f"event '{ev.kind}' at {ev.at} moves '{m}' while the event "
                           f"at line {busy[m][2]} still moves it (until {busy[m][1]:g} s)",
                           ev.line)
            busy[m] = (ev.at, end, ev.line)


def _check_fits(scn: Scenario, inner: ObjectSpec, outer: ObjectSpec, line: int | None) -> None:
    if not outer.is_container:
        raise _err(scn, f"'{inner.id}' cannot go under '{outer.id}': a {outer.shape} is not a "
                   "container (cup, mug, box or mesh)", line)
    if outer.shape in ("cup", "mug") and not outer.upside_down:
        raise _err(scn, f"'{inner.id}' cannot go under '{outer.id}': the {outer.shape} is "
                   "upright (upside_down: false)", line)
    r_in = inner.footprint_radius() if inner.shape != "box" else \
        math.hypot(*inner.half_extents()[:2])
    if inner.shape == "mug":
        r_in = inner.radius
    if r_in > outer.inner_radius() + 1e-9 or 2 * inner.half_extents()[2] > outer.inner_height():
        raise _err(scn, f"'{inner.id}' does not fit under '{outer.id}'", line)


def _event_movers(ev: Event) -> list[str]:
    p = ev.params
    if ev.kind in ("move", "lift", "pick_up", "put_down"):
        return [p.get("object") or p.get("container")]
    if ev.kind == "put_under":
        return [p["container"], p["object"]]
    if ev.kind == "swap":
        return [p["a"], p["b"]]
    if ev.kind == "shuffle":
        return list(p["containers"])
    return []


def _check_event(scn: Scenario, ev: Event, ids: dict[str, ObjectSpec],
                 where: dict[str, tuple[float, float]]) -> None:
    p = ev.params

    def need(key: str) -> Any:
        if key not in p:
            raise _err(scn, f"event '{ev.kind}' needs '{key}'", ev.line)
        return p[key]

    def known(oid: str) -> ObjectSpec:
        if oid not in ids:
            raise _err(scn, f"event '{ev.kind}' names unknown object '{oid}' "
                       f"(known: {', '.join(ids)})", ev.line)
        return ids[oid]

    p.setdefault("duration", {"cover_camera": 2.0, "remove": 0.0, "move": 0.0}.get(ev.kind, 2.0))
    if ev.kind == "move":
        known(need("object"))
        need("to")
        if "speed" in p and "duration" in p and p["duration"]:
            raise _err(scn, "event 'move': give 'speed' or 'duration', not both", ev.line)
        if not p.get("duration"):
            pts = [where[p["object"]], *[v[:2] for v in p.get("via", [])], p["to"][:2]]
            # estimated from where the object should be; the timeline measures it again
            length = sum(math.dist(a, b) for a, b in zip(pts, pts[1:], strict=False))
            p["duration"] = max(length / p.get("speed", 0.15), 0.1)
            p["estimated_duration"] = True
        where[p["object"]] = (p["to"][0], p["to"][1])
    elif ev.kind in ("pick_up", "remove"):
        known(need("object"))
    elif ev.kind == "put_down":
        known(need("object"))
        need("to")
        where[p["object"]] = (p["to"][0], p["to"][1])
    elif ev.kind == "put_under":
        inner = known(need("object"))
        outer = known(need("container"))
        if inner.id == outer.id:
            raise _err(scn, "event 'put_under': an object cannot go under itself", ev.line)
        _check_fits(scn, inner, outer, ev.line)
        mover = p.setdefault("move", "container")
        if mover not in ("container", "object"):
            raise _err(scn, f"event 'put_under': 'move' must be 'container' or 'object', got "
                       f"'{mover}'", ev.line)
        if mover == "container":
            where[outer.id] = where[inner.id]
        else:
            where[inner.id] = where[outer.id]
    elif ev.kind == "lift":
        cont = known(need("container"))
        if not cont.is_container:
            raise _err(scn, f"event 'lift': '{cont.id}' is not a container", ev.line)
        x, y = where[cont.id]
        to = p.get("to", (x, y + 0.13))
        where[cont.id] = (to[0], to[1])
    elif ev.kind == "swap":
        a, b = known(need("a")), known(need("b"))
        if a.id == b.id:
            raise _err(scn, "event 'swap': 'a' and 'b' are the same object", ev.line)
        where[a.id], where[b.id] = where[b.id], where[a.id]
    elif ev.kind == "shuffle":
        conts = need("containers")
        order = need("order")
        for c in conts:
            known(c)
        if sorted(order) != sorted(conts) or len(set(conts)) != len(conts):
            raise _err(scn, "event 'shuffle': 'order' must be a permutation of 'containers'",
                       ev.line)
        before = dict(where)
        for c, o in zip(conts, order, strict=True):
            where[c] = before[o]
    elif ev.kind == "cover_camera":
        pass
