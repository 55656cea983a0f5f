#!/usr/bin/python3
"""test_movies.py: `ballfilm animate` renders every model.

For each model a short run is rendered to 10 frames at 320x240; ffprobe
(Debian's ffmpeg) must count 10 frames of 320x240 in the MP4.  Then the
same with ffmpeg taken off PATH: the movie must come out as a GIF of 10
frames through Pillow, and stderr must say why.

usage: test_movies.py BIN/ballfilm WORKDIR   (make test-movies)
Ends with the line 'movies: N passed, N failed'; exit 1 on a failure."""
import json
import os
import shutil
import sys

from pychecks import Checks, run, run_scene

FRAMES, W, H = 10, 320, 240

# name: scene and overrides of a run of a few seconds at most
RUNS = {
    "balls": ("runs/two_balls_B.ini", ["scene.t_end=1"]),
    "film": ("runs/kink_steady.ini", ["scene.t_end=1",
                                      "scene.output_every=0.1 s",
                                      "film.profile_every=0.1 s"]),
    "coupled": ("runs/coupled_fig8.ini", ["scene.t_end=0.02",
                                          "film.profile_every=0.002 s"]),
    "greenspan72": ("runs/greenspan72_ex2.ini", ["scene.t_end=1",
                                                 "scene.output_every=5"]),
    "greenspan73": ("runs/greenspan73_penetration.ini", []),
    "mac": ("runs/stratres.ini", ["scene.t_end=1", "scene.output_every=2"]),
}

CK = Checks("movies")
check = CK.check


def probe(path):
    """(frames, width, height) of a video as ffprobe counts them."""
    r = run(["ffprobe", "-v", "error", "-count_frames", "-select_streams",
             "v:0", "-show_entries", "stream=nb_read_frames,width,height",
             "-of", "json", path])
    if r.returncode:
        return None
    s = json.loads(r.stdout)["streams"][0]
    return int(s["nb_read_frames"]), int(s["width"]), int(s["height"])


def main(prog, work):
    if not shutil.which("ffprobe"):
        print("SKIP  movies: ffprobe not found (Debian package ffmpeg; "
              "make test-movies installs it as root)")
        print("movies: 0 passed, 0 failed, 1 skipped")
        return 0
    os.makedirs(work, exist_ok=True)
    for name, (scene, sets) in RUNS.items():
        h5 = os.path.join(work, name + ".h5")
        r = run_scene(prog, scene, h5, sets)
        check(r.returncode == 0, "%s: run %s" % (name, scene), r.stderr)
        if r.returncode:
            continue
        mp4 = os.path.join(work, name + ".mp4")
        r = run([prog, "animate", h5, "-o", mp4, "--frames", str(FRAMES),
                 "--size", "%dx%d" % (W, H), "-q"])
        check(r.returncode == 0, "%s: animate" % name, r.stderr[-2000:])
        got = probe(mp4) if r.returncode == 0 else None
        check(got == (FRAMES, W, H), "%s: MP4 has %d frames of %dx%d"
              % (name, FRAMES, W, H), "ffprobe says %s" % (got,))
    # the GIF fallback: no ffmpeg on PATH
    empty = os.path.join(work, "no-ffmpeg-bin")
    os.makedirs(empty, exist_ok=True)
    env = dict(os.environ, PATH=empty)
    h5 = os.path.join(work, "greenspan73.h5")
    out = os.path.join(work, "fallback.mp4")
    gif = os.path.join(work, "fallback.gif")
    for f in (out, gif):
        if os.path.exists(f):
            os.remove(f)
    r = run([os.path.abspath(prog), "animate", h5, "-o", out, "--frames",
             str(FRAMES), "--size", "%dx%d" % (W, H), "-q"], env=env)
    check(r.returncode == 0, "fallback: animate without ffmpeg", r.stderr)
    check("ffmpeg is not on PATH" in r.stderr and gif in r.stderr,
          "fallback: says that ffmpeg is missing and names the GIF",
          r.stderr)
    check(not os.path.exists(out), "fallback: no MP4 written")
    try:
        from PIL import Image
        with Image.open(gif) as im:
            got = (im.n_frames, im.size[0], im.size[1])
    except Exception as e:  # noqa: BLE001 - any failure is the test's
        got = str(e)
    check(got == (FRAMES, W, H), "fallback: GIF has %d frames of %dx%d"
          % (FRAMES, W, H), "got %s" % (got,))
    return CK.done()


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
