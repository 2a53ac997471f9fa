"""Projection, drawing of anchors and particles, PNG, GIF, video and the top-down plot."""

from __future__ import annotations

import imageio.v3 as iio
import numpy as np
import pytest

from probanchor.visualise import (
    AnchorView,
    CameraView,
    VideoWriter,
    anchor_colour,
    draw_anchors,
    draw_particles,
    plot_topdown,
    render_topdown,
    save_png,
    write_gif,
    write_video,
)

INTR = (100.0, 120.0, 160.0, 120.0)  # fx, fy, cx, cy for 320x240


def looking_down(height=1.0):
    """World-from-camera pose of a camera at (0, 0, height) looking straight down, image x
    along world x (so image y, downwards, is world -y)."""
    pose = np.eye(4)
    pose[:3, 0] = (1, 0, 0)
    pose[:3, 1] = (0, -1, 0)
    pose[:3, 2] = (0, 0, -1)
    pose[:3, 3] = (0, 0, height)
    return pose


def test_projection_of_known_points():
    cam = CameraView.make(INTR, np.eye(4))
    uv, z = cam.project(np.array([[0.1, -0.2, 1.0], [0.0, 0.0, 2.0], [0.0, 0.0, -1.0]]))
    # u = cx + fx x / z = 160 + 100 * 0.1 = 170; v = cy + fy y / z = 120 - 120 * 0.2 = 96.
    assert uv[0] == pytest.approx([170.0, 96.0])
    assert uv[1] == pytest.approx([160.0, 120.0]) and z[1] == 2.0
    assert np.all(np.isnan(uv[2]))  # behind the camera

    down = CameraView.make(INTR, looking_down())
    uv, z = down.project(np.array([0.1, 0.2, 0.0]))
    # In the camera: (0.1, -0.2, 1.0) -> (170, 96), 1 m away.
    assert uv[0] == pytest.approx([170.0, 96.0]) and z[0] == pytest.approx(1.0)
    # The same camera given as camera-from-world projects the same.
    inv = CameraView.make(INTR, np.linalg.inv(looking_down()), convention="camera_from_world")
    assert inv.project(np.array([0.1, 0.2, 0.0]))[0] == pytest.approx(uv)
    assert np.allclose(inv.camera_from_world @ looking_down(), np.eye(4))


def test_projection_accepts_objects_with_intrinsics_and_rejects_bad_poses():
    class Intr:
        fx, fy, cx, cy = INTR

    cam = CameraView.make(Intr(), looking_down())
    assert cam.project(np.zeros(3))[0][0] == pytest.approx([160.0, 120.0])
    with pytest.raises(ValueError, match="4x4"):
        CameraView.make(INTR, np.eye(3))
    with pytest.raises(ValueError, match="convention"):
        CameraView.make(INTR, np.eye(4), convention="opengl")


def grey():
    return np.full((240, 320, 3), 128, np.uint8)


def test_particles_change_the_image_where_they_land_with_alpha_by_weight():
    cam = CameraView.make(INTR, looking_down())
    colour = (255, 0, 0)
    # heavy lands on pixel (170, 96), light on (130, 144)
    heavy, light = np.array([0.1, 0.2, 0.0]), np.array([-0.3, -0.2, 0.0])
    pts = np.vstack([np.repeat(heavy[None], 5, 0), np.repeat(light[None], 5, 0)])
    w = np.array([1.0] * 5 + [0.25] * 5)
    out = draw_particles(grey(), cam, pts, colour, w, radius=1, max_alpha=0.8)
    changed = np.any(out != 128, axis=2)
    assert changed[96, 170] and changed[144, 130]
    assert changed[96, 171] and changed[97, 170]  # the dot has a radius
    assert changed.sum() <= 2 * 9  # nothing else
    # Alpha 0.8 at the heavy dot, 0.8 * 0.25 = 0.2 at the light one: red = 128 + a * 127.
    assert out[96, 170, 0] == round(128 + 0.8 * 127) and out[96, 170, 1] == round(128 * 0.2)
    assert out[144, 130, 0] == round(128 + 0.2 * 127)


def test_draw_anchors_labels_and_leaves_the_input_alone():
    cam = CameraView.make(INTR, looking_down())
    rgb = grey()
    rng = np.random.default_rng(0)
    hidden = AnchorView("ball-1", np.array([0.1, 0.2, 0.0]), perceived=False,
                        particles=rng.normal([0.1, 0.2, 0.0], 0.01, (300, 3)),
                        weights=rng.random(300))
    seen = AnchorView("mug-1", np.array([-0.3, -0.2, 0.0]), perceived=True,
                      bbox=(120, 130, 140, 158))
    out = draw_anchors(rgb, cam, [hidden, seen])
    assert np.all(rgb == 128)
    changed = np.any(out != 128, axis=2)
    assert changed[93:100, 167:174].mean() > 0.5  # particles around (170, 96)
    assert changed[130, 120:141].all()  # the top edge of the mug's box
    r, g, b = anchor_colour("ball-1")
    assert np.any(np.all(out == (r, g, b), axis=2))  # text or dots in the ball's colour
    assert anchor_colour("ball-1") == anchor_colour("ball-1")
    with pytest.raises(ValueError, match="RGB uint8"):
        draw_anchors(rgb.astype(float), cam, [])


def test_png_and_gif(tmp_path):
    cam = CameraView.make(INTR, looking_down())
    frames = []
    for k in range(5):  # a ball moving to the right: every frame differs
        a = AnchorView("ball-1", np.array([-0.2 + 0.1 * k, 0.0, 0.0]), perceived=True)
        frames.append(draw_anchors(grey(), cam, [a]))
    png = save_png(tmp_path / "frames" / "0000.png", frames[0])
    assert np.array_equal(iio.imread(png), frames[0])
    assert write_gif(tmp_path / "run.gif", frames, fps=5) == 5
    gif = iio.imread(tmp_path / "run.gif", index=None)
    assert gif.shape[0] == 5 and gif.shape[1:3] == (240, 320)
    assert write_gif(tmp_path / "from_files.gif", [png, png]) == 2
    with pytest.raises(ValueError, match="differ in size"):
        write_gif(tmp_path / "bad.gif", [frames[0], frames[0][:100]])
    with pytest.raises(ValueError, match="no frames"):
        write_gif(tmp_path / "empty.gif", [])


def decode(path):
    import av

    with av.open(str(path)) as container:
        frames = list(container.decode(video=0))
        return [f.to_ndarray(format="rgb24") for f in frames], [float(f.time) for f in frames]


@pytest.mark.parametrize("suffix", [".mp4", ".webm"])
def test_video_decodes_to_the_frames_at_their_times(tmp_path, suffix):
    cam = CameraView.make(INTR, looking_down())
    # more frames than the encoders' look-ahead: packets come out while frames still go in
    frames = [draw_anchors(grey(), cam, [AnchorView("ball-1", np.array([-0.2 + 0.004 * k, 0, 0]),
                                                    perceived=True)]) for k in range(100)]
    path = tmp_path / f"run{suffix}"
    with VideoWriter(path) as video:
        for k, f in enumerate(frames):
            video.add(f, time=10.0 + k / 5)  # 5 frames per second, from 10 s on
    images, times = decode(path)
    assert len(images) == 100 and images[0].shape == (240, 320, 3)
    assert times[0] == pytest.approx(0.0) and times[-1] == pytest.approx(99 / 5, abs=0.002)
    # lossy, but close: the mean error per pixel is small
    assert np.abs(images[7].astype(int) - frames[7]).mean() < 4
    assert path.stat().st_size < 100_000
    # from PNG files, an odd size padded to even
    png = save_png(tmp_path / "odd.png", frames[0][:239, :319])
    assert write_video(tmp_path / "odd.mp4", [png, png, png], fps=10) == 3
    images, times = decode(tmp_path / "odd.mp4")
    assert images[0].shape == (240, 320, 3) and times[1] == pytest.approx(0.1)


def test_video_rejects_bad_input(tmp_path):
    with pytest.raises(ValueError, match=r"\.mp4 or \.webm"):
        VideoWriter(tmp_path / "run.avi")
    with pytest.raises(ValueError, match="positive"):
        VideoWriter(tmp_path / "run.mp4", fps=0)
    with pytest.raises(ValueError, match="no frames"):
        write_video(tmp_path / "none.mp4", [])
    video = VideoWriter(tmp_path / "run.mp4")
    with pytest.raises(ValueError, match="not an RGB uint8"):
        video.add(grey().astype(float))
    video.add(grey(), time=1.0)
    with pytest.raises(ValueError, match="320x240"):
        video.add(grey()[:100])
    with pytest.raises(ValueError, match="before the previous"):
        video.add(grey(), time=0.5)
    assert video.close() == tmp_path / "run.mp4" and video.frames == 1
    assert VideoWriter(tmp_path / "empty.mp4").close() is None  # nothing added: no file
    assert not (tmp_path / "empty.mp4").exists()


def test_topdown_plot_shows_every_mode(tmp_path):
    rng = np.random.default_rng(1)
    mugs = np.array([[0.0, 0.0, 0.05], [0.2, 0.0, 0.05], [0.4, 0.1, 0.05]])
    pts = np.concatenate([rng.normal(m, 0.01, (200, 3)) for m in mugs])
    ball = AnchorView("ball-1", mugs[0], perceived=False, particles=pts, weights=np.ones(600))
    seen = [AnchorView(f"mug-{i + 1}", m, perceived=True) for i, m in enumerate(mugs)]
    img = render_topdown([ball, *seen], truth={"ball_1": {"position": mugs[1], "visible": False}},
                         extent=(-0.1, 0.5, -0.1, 0.2))
    assert img.dtype == np.uint8 and img.shape == (400, 500, 3)
    colour = np.array(anchor_colour("ball-1"))
    near = np.all(np.abs(img.astype(int) - colour) < 40, axis=2)
    cols = np.nonzero(near.any(axis=0))[0]
    # The ball's dots spread over the three modes, 0.4 m of a 0.6 m wide axis.
    assert cols.max() - cols.min() > 0.5 * img.shape[1] * 0.4 / 0.6
    path = plot_topdown(tmp_path / "top.png", [ball, *seen])
    assert iio.imread(path).shape[2] in (3, 4)
