#!/usr/bin/python3
"""test_movies.py: `ballfilm animate` renders every model.

For each model a short run is rendered to 10 frames at 320x240; ffprobe
(Debian's ffmpeg) must count 10 frames of 320x240 in the MP4.  Then the
same with ffmpeg taken off PATH: the movie must come out as a GIF of 10
frames through Pillow, and stderr must say why.

Memory: a 200704-particle run (runs/greenspan72_large.ini) with its
positions at every one of 400 steps (401 rows, 1.29 GB of positions) is
rendered to 100 frames; the renderer's peak resident memory must stay
under 1 GiB.  Loading the rows instead of reading them one frame at a
time would need more than the 1.29 GB, so this fails if the thinning is
lost.  The file is removed afterwards.

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


LARGE_ROWS, LARGE_FRAMES, GIB = 400, 100, 1 << 30

# peak resident memory (bytes) of a command, as its parent sees it
PEAK_RSS = ("import resource, subprocess, sys\n"
            "r = subprocess.run(sys.argv[1:])\n"
            "print(r.returncode, "
            "resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024)")


def large_movie(prog, work):
    """the 200704-particle render stays under 1 GiB"""
    h5 = os.path.join(work, "large.h5")
    r = run_scene(prog, "runs/greenspan72_large.ini", h5,
                  ["scene.t_end=%g" % (LARGE_ROWS * 1e-2),
                   "scene.output_every=1", "greenspan72.particles_every=1"])
    check(r.returncode == 0, "large: run of 200704 particles", r.stderr)
    if r.returncode:
        return
    size = os.path.getsize(h5)
    mp4 = os.path.join(work, "large.mp4")
    r = run([sys.executable, "-c", PEAK_RSS, prog, "animate", h5, "-o", mp4,
             "--frames", str(LARGE_FRAMES), "-q"])
    try:
        status, peak = (int(x) for x in r.stdout.split()[-2:])
    except ValueError:
        status, peak = -1, -1
    os.remove(h5)
    check(status == 0, "large: animate", r.stderr[-2000:])
    check(0 < peak < GIB and size > GIB,
          "large: %d frames of a %.2f GB file in %.0f MiB (limit 1024 MiB)"
          % (LARGE_FRAMES, size / 1e9, peak / 2**20))
    got = probe(mp4) if status == 0 else None
    check(got is not None and got[0] == LARGE_FRAMES,
          "large: MP4 has %d frames" % LARGE_FRAMES, "ffprobe says %s" % (got,))


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
    large_movie(prog, work)
    return CK.done()


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
