"""Build scenarios in Python (the same checks as files; ``to_yaml`` writes the file form).

    b = ScenarioBuilder("demo", fps=15)
    b.add("ball_1", "ball", "red", position=(0.0, 0.05))
    b.add("mug_1", "mug", "blue", position=(0.15, 0.05))
    b.put_under(1.0, "ball_1", "mug_1", duration=2.0)
    scenario = b.build()
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from probanchor.tabletop.scenario import Scenario, parse_scenario


def _plain(value: Any) -> Any:
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    if isinstance(value, list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if hasattr(value, "item"):  # numpy scalars
        return value.item()
    return value


class ScenarioBuilder:
    def __init__(self, name: str, fps: float = 15.0, duration: float | None = None,
                 camera: dict[str, Any] | None = None, noise: dict[str, Any] | bool | None = None
                 ) -> None:
        self.data: dict[str, Any] = {"name": name, "fps": fps, "objects": [], "events": []}
        if duration is not None:
            self.data["duration"] = duration
        if camera:
            self.data["camera"] = dict(camera)
        if noise is not None:
            self.data["noise"] = noise

    # objects
    def add(self, oid: str, category: str, colour: str | tuple[float, float, float],
            position: tuple[float, ...] | None = None, under: str | None = None,
            **params: Any) -> ScenarioBuilder:
        """Add an object; ``params`` are shape, radius, height, size, yaw, upside_down."""
        obj: dict[str, Any] = {"id": oid, "category": category, "colour": colour}
        if position is not None:
            obj["position"] = position
        if under is not None:
            obj["under"] = under
        obj.update(params)
        self.data["objects"].append(_plain(obj))
        return self

    # events
    def event(self, at: float, do: str, **params: Any) -> ScenarioBuilder:
        ev = {"at": at, "do": do}
        ev.update({k: v for k, v in params.items() if v is not None})
        self.data["events"].append(_plain(ev))
        return self

    def move(self, at: float, obj: str, to: tuple[float, ...], via: list[Any] | None = None,
             speed: float | None = None, duration: float | None = None) -> ScenarioBuilder:
        return self.event(at, "move", object=obj, to=to, via=via, speed=speed,
                          duration=duration)

    def pick_up(self, at: float, obj: str, duration: float = 2.0, hand: str | None = None
                ) -> ScenarioBuilder:
        return self.event(at, "pick_up", object=obj, duration=duration, hand=hand)

    def put_down(self, at: float, obj: str, to: tuple[float, ...], duration: float = 2.0
                 ) -> ScenarioBuilder:
        return self.event(at, "put_down", object=obj, to=to, duration=duration)

    def put_under(self, at: float, obj: str, container: str, duration: float = 2.0,
                  move: str | None = None) -> ScenarioBuilder:
        """``move="object"`` slides the object under the container where it stands; by
        default the container is carried over the object."""
        return self.event(at, "put_under", object=obj, container=container, duration=duration,
                          move=move)

    def lift(self, at: float, container: str, to: tuple[float, ...] | None = None,
             duration: float = 2.0, height: float | None = None) -> ScenarioBuilder:
        return self.event(at, "lift", container=container, to=to, duration=duration,
                          height=height)

    def swap(self, at: float, a: str, b: str, duration: float = 2.0) -> ScenarioBuilder:
        return self.event(at, "swap", a=a, b=b, duration=duration)

    def shuffle(self, at: float, containers: list[str], order: list[str],
                duration: float = 4.0) -> ScenarioBuilder:
        return self.event(at, "shuffle", containers=containers, order=order, duration=duration)

    def cover_camera(self, at: float, duration: float = 2.0) -> ScenarioBuilder:
        return self.event(at, "cover_camera", duration=duration)

    def remove(self, at: float, obj: str) -> ScenarioBuilder:
        return self.event(at, "remove", object=obj)

    # output
    def to_dict(self) -> dict[str, Any]:
        return _plain(self.data)

    def to_yaml(self) -> str:
        return yaml.safe_dump(self.to_dict(), sort_keys=False, default_flow_style=None)

    def build(self, source: str | None = None) -> Scenario:
        """Validate and return the scenario (raises ScenarioError like a file would)."""
        return parse_scenario(self.to_dict(), source or f"<builder {self.data['name']}>")

    def save(self, path: str | Path) -> Scenario:
        Path(path).write_text(self.to_yaml(), encoding="utf-8")
        from probanchor.tabletop.scenario import load_scenario

        return load_scenario(path)
