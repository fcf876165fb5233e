# SPDX-License-Identifier: Apache-2.0
"""output_faults.py - faults while rtcl writes a file (tests/cli_outputs.sh).

  output_faults.py kill RTCL DIR ROUNDS [EXT]
      A good image is written to DIR/out.EXT (pfm unless EXT is given);
      then, ROUNDS times, a render of another image to the same name is
      killed with SIGKILL at a random point while its file is being written
      (seen as its temporary, .out.tmp-*.EXT, existing), or at a random time
      of the whole run. Each time DIR/out.EXT must be byte for byte the old
      image or the new one (killed after its rename), never a part, and no
      other file than a killed writer's temporary may appear.

  output_faults.py interleave RTCL DIR EXT
      Two renders of different images to DIR/out.EXT; the first is stopped
      (SIGSTOP) while it writes, the second runs to the end, then the first
      is continued. Both must say "wrote" and exit 0, and the file must be
      the whole image of the one that finished last.

  output_faults.py interrupt RTCL DIR
      SIGINT, SIGTERM and SIGHUP while rtcl writes: a render to DIR/out.pfm
      gets the signal while its temporary exists, and a video (when ffmpeg
      is on PATH) while ffmpeg writes it. rtcl must end by that signal, the
      old file must be as it was and no temporary may be left (rtcl's
      handler removes them and stops ffmpeg first).

Exit 0 when every check holds; the failures are printed.
"""

import glob
import os
import random
import shutil
import signal
import subprocess
import sys
import time

SCENE = "builtin:cornell"


def render_args(rtcl, out, width, height):
    return [rtcl, "render", SCENE, "--direct", "--threads", "2", "--width", str(width),
            "--height", str(height), "-o", out]


def run_ok(args):
    done = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        raise SystemExit("setup failed: %s: %s" % (" ".join(args), done.stdout))


def read(path):
    with open(path, "rb") as f:
        return f.read()


def temporaries(folder, stem, ext):
    return glob.glob(os.path.join(folder, ".%s.tmp-*%s" % (stem, ext)))


def wait_for_temporary(proc, folder, stem, ext, limit_s=120.0):
    """Polls until the process's temporary appears (True) or it exits (False)."""
    end = time.monotonic() + limit_s
    while time.monotonic() < end:
        if temporaries(folder, stem, ext):
            return True
        if proc.poll() is not None:
            return False
        time.sleep(0.0002)
    return False


def kill(rtcl, folder, rounds, ext):
    failures = []
    old_path = os.path.join(folder, "old." + ext)
    new_path = os.path.join(folder, "new." + ext)
    out = os.path.join(folder, "out." + ext)
    run_ok(render_args(rtcl, old_path, 640, 640))
    run_ok(render_args(rtcl, new_path, 1024, 1024))
    old, new = read(old_path), read(new_path)
    rng = random.Random(31)
    during = 0
    # A whole run's time, for the kills at any moment.
    start = time.monotonic()
    run_ok(render_args(rtcl, out, 1024, 1024))
    whole_s = time.monotonic() - start
    for k in range(rounds):
        with open(out, "wb") as f:
            f.write(old)
        for t in temporaries(folder, "out", "." + ext):
            os.unlink(t)
        proc = subprocess.Popen(render_args(rtcl, out, 1024, 1024), stdout=subprocess.DEVNULL,
                                stderr=subprocess.DEVNULL)
        in_write = k % 2 == 0
        if in_write:
            seen = wait_for_temporary(proc, folder, "out", "." + ext)
            time.sleep(rng.uniform(0.0, 0.004))
        else:
            time.sleep(rng.uniform(0.0, whole_s * 1.1))
            seen = False
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        now = read(out)
        if in_write:
            if not seen:
                failures.append("round %d: no temporary was seen while the file was written" % k)
                continue
            during += 1
            if proc.returncode == -signal.SIGKILL and now != old and now != new:
                failures.append("round %d: killed while writing, out.%s is %d bytes, neither "
                                "the old (%d) nor the new image (%d)" % (k, ext, len(now),
                                                                        len(old), len(new)))
            elif proc.returncode == -signal.SIGKILL and now != old and now == new:
                pass  # killed after the rename: the new file, whole
        elif now != old and now != new:
            failures.append("round %d: killed at a random time, out.%s is %d bytes, neither the "
                            "old nor the new image" % (k, ext, len(now)))
        strays = sorted(set(os.listdir(folder)) - {"old." + ext, "new." + ext, "out." + ext} -
                        {os.path.basename(t) for t in temporaries(folder, "out", "." + ext)})
        if strays:
            failures.append("round %d: other files appeared: %s" % (k, ", ".join(strays)))
    print("kill %s: %d rounds, %d killed while writing, %d failures" % (ext, rounds, during,
                                                                         len(failures)))
    return failures


def interleave(rtcl, folder, ext):
    failures = []
    a_ref = os.path.join(folder, "a_ref." + ext)
    b_ref = os.path.join(folder, "b_ref." + ext)
    out = os.path.join(folder, "out." + ext)
    run_ok(render_args(rtcl, a_ref, 1024, 1024))
    run_ok(render_args(rtcl, b_ref, 640, 480))
    # The first writer is stopped while its temporary exists; a writer that
    # got past its rename before the stop took effect, or whose temporary lived
    # too briefly for the poll to see on a loaded machine, is tried again.
    seen = 0
    for attempt in range(20):
        first = subprocess.Popen(render_args(rtcl, out, 1024, 1024), stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, text=True)
        if not wait_for_temporary(first, folder, "out", "." + ext):
            first.communicate()
            if first.returncode != 0:
                return ["interleave %s: the first writer exited %s" % (ext, first.returncode)]
            continue
        seen += 1
        first.send_signal(signal.SIGSTOP)
        time.sleep(0.05)
        if temporaries(folder, "out", "." + ext):
            break
        first.send_signal(signal.SIGCONT)
        first.communicate()
    else:
        if seen == 0:
            return ["interleave %s: the first writer's temporary never appeared in 20 tries" % ext]
        return ["interleave %s: the first writer could never be stopped while writing" % ext]
    second = subprocess.run(render_args(rtcl, out, 640, 480), stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    first.send_signal(signal.SIGCONT)
    first_out, _ = first.communicate()
    for name, rc, text in (("first", first.returncode, first_out),
                           ("second", second.returncode, second.stdout)):
        if rc != 0 or "wrote" not in text:
            failures.append("interleave %s: the %s writer exited %s: %s" % (ext, name, rc, text))
    if read(out) != read(a_ref):
        failures.append("interleave %s: out.%s is not the image of the writer that renamed "
                        "last (%d bytes, expected %d)" % (ext, ext, len(read(out)),
                                                         len(read(a_ref))))
    if temporaries(folder, "out", "." + ext):
        failures.append("interleave %s: a temporary was left behind" % ext)
    print("interleave %s: %d failures" % (ext, len(failures)))
    return failures


def interrupt(rtcl, folder):
    failures = []
    out = os.path.join(folder, "out.pfm")
    old_path = os.path.join(folder, "old.pfm")
    run_ok(render_args(rtcl, old_path, 64, 64))
    old = read(old_path)
    jobs = [("pfm", render_args(rtcl, out, 1024, 1024), out, old)]
    if shutil.which("ffmpeg"):
        video = os.path.join(folder, "v.mp4")
        with open(video, "wb") as f:
            f.write(b"an old video")
        scene = os.path.join(os.environ.get("RT_SOURCE_DIR", "."), "scenes",
                             "keyframes_animated.json")
        jobs.append(("mp4", [rtcl, "animate", scene, "--fps", "10", "--frames", "100000",
                             "--width", "64", "--height", "64", "-o", video], video,
                     b"an old video"))
    for ext, args, target, before in jobs:
        stem = os.path.splitext(os.path.basename(target))[0]
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            for attempt in range(20):
                with open(target, "wb") as f:
                    f.write(before)
                proc = subprocess.Popen(args, stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL)
                if not wait_for_temporary(proc, folder, stem, "." + ext):
                    proc.wait()
                    failures.append("%s %s: the temporary never appeared" % (ext, sig.name))
                    break
                if ext == "mp4":
                    time.sleep(0.3)  # ffmpeg has started and writes
                proc.send_signal(sig)
                proc.wait()
                if proc.returncode == 0:
                    continue  # it finished before the signal: again
                if proc.returncode != -sig:
                    failures.append("%s %s: exit status %d, not the signal" % (ext, sig.name,
                                                                              proc.returncode))
                time.sleep(0.2)
                if read(target) != before:
                    failures.append("%s %s: the old file changed" % (ext, sig.name))
                left = temporaries(folder, stem, "." + ext)
                if left:
                    failures.append("%s %s: temporaries left: %s" % (ext, sig.name,
                                                                     ", ".join(left)))
                    for t in left:
                        os.unlink(t)
                break
            else:
                failures.append("%s %s: never interrupted while writing" % (ext, sig.name))
    print("interrupt: %d jobs, %d failures" % (len(jobs), len(failures)))
    return failures


def main():
    mode, rtcl, folder = sys.argv[1], sys.argv[2], sys.argv[3]
    if mode == "kill":
        failures = kill(rtcl, folder, int(sys.argv[4]), sys.argv[5] if len(sys.argv) > 5 else "pfm")
    elif mode == "interrupt":
        failures = interrupt(rtcl, folder)
    else:
        failures = interleave(rtcl, folder, sys.argv[4])
    for f in failures:
        print("FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
