#!/usr/bin/python3
"""Output that does not slow down: the tumbling box (inputs/tumbling_box.xml, Mesh/size 0.5) run
for --steps steps (Time/dt 0.01) with a field frame at every step (Output/every = 1), the frame
files in its directory counted every --window seconds; then the same model without fields
(Output/every = 0) for --reference seconds, its monitors.csv rows counted the same way. A writer whose cost per frame
grows with the frames written so far (an index rewritten whole at every frame) shows as a
falling count per window; a steady count is O(1) per frame. Writes perf/results/output_rate.json
and the table in perf/README.md between <!-- output_rate:begin --> and <!-- output_rate:end -->.

    /usr/bin/python3 perf/output_rate.py [--build build] [--steps 100000] [--window 10]
        [--reference 60]
"""
import argparse, datetime, json, os, shutil, signal, subprocess, sys, tempfile, time
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_util import ENV, ROOT, replace_section  # noqa: E402


def count(out, every):
    """Frames written (every > 0) or monitors rows flushed (every = 0) so far."""
    try:
        if every > 0:
            return sum(1 for f in os.listdir(out) if f.startswith('fields_') and f.endswith('.h5'))
        with open(os.path.join(out, 'monitors.csv')) as f:
            return max(0, sum(1 for _ in f) - 1)
    except OSError:
        return 0


def run(build, every, steps, window, seconds=None):
    """Per-window counts of one run of `steps` steps (stopped with SIGTERM after `seconds`)."""
    tmp = tempfile.mkdtemp(prefix='emc-output-rate-')
    out = os.path.join(tmp, 'out')
    cmd = [os.path.join(ROOT, build, 'bin', 'emcontact'), os.path.join(ROOT, 'inputs', 'tumbling_box.xml'),
           '--set', 'Bodies/box/Mesh/size=0.5', '--set', 'Time/dt=0.01', '--set', 'Time/end=%g' % (0.01 * steps),
           '--set', 'Output/every=%d' % every, '--set', 'Output/progress=false', '--output', out]
    p = subprocess.Popen(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    counts, last, k = [], 0, 0
    t0 = time.time()
    while p.poll() is None and (seconds is None or k * window < seconds):
        k += 1
        while p.poll() is None and time.time() < t0 + k * window:
            time.sleep(0.05)
        if p.poll() is not None:
            break  # a last, partial window is not counted
        now = count(out, every)
        counts.append(now - last)
        last = now
    if p.poll() is None:
        p.send_signal(signal.SIGTERM)
    err = p.communicate()[1].decode()
    if p.returncode not in (0, 1) or (p.returncode == 1 and 'stopped by SIGTERM' not in err):
        sys.exit('emcontact failed: ' + err)
    size = os.path.getsize(os.path.join(out, 'fields.xdmf')) if every > 0 else 0
    total = count(out, every)
    shutil.rmtree(tmp)
    return counts, size, total, time.time() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--build', default='build')
    ap.add_argument('--steps', type=int, default=100000)
    ap.add_argument('--window', type=float, default=10)
    ap.add_argument('--reference', type=float, default=60)
    a = ap.parse_args()
    frames, xdmf, total, wall = run(a.build, 1, a.steps, a.window)
    rows, _, _, _ = run(a.build, 0, a.steps, a.window, a.reference)
    res = {'date': datetime.date.today().isoformat(), 'steps': a.steps, 'window_s': a.window,
           'frames_per_window': frames, 'frames': total, 'wall_s': wall,
           'steps_per_window_without_fields': rows, 'fields_xdmf_bytes': xdmf}
    json.dump(res, open(os.path.join(ROOT, 'perf', 'results', 'output_rate.json'), 'w'), indent=1)
    n = len(frames)
    tenth = max(1, n // 10)
    first, mid, late = frames[:tenth], frames[(n - tenth) // 2:(n + tenth) // 2], frames[-tenth:]
    mean = lambda v: sum(v) / len(v)
    text = ('Measured %s with `/usr/bin/python3 perf/output_rate.py --steps %d --window %g` (the tumbling box, '
            'Mesh/size 0.5, Time/dt 0.01, a frame at every step: %d frames in %.0f s, fields.xdmf %.1f MB at the '
            'end). Steps (= frames) per %g s window, the mean of the first, middle and last tenth of the windows, '
            'and the same model without fields for %g s:\n\n'
            % (res['date'], a.steps, a.window, total, wall, xdmf / 1e6, a.window, a.reference))
    text += '| | first tenth | middle tenth | last tenth | min | max |\n|---|---|---|---|---|---|\n'
    text += '| steps per window, Output/every = 1 | %.0f | %.0f | %.0f | %d | %d |\n' % (
        mean(first), mean(mid), mean(late), min(frames), max(frames))
    text += '| steps per window, Output/every = 0 | %.0f | | | %d | %d |\n\n' % (mean(rows), min(rows), max(rows))
    text += ('Last tenth against the first: %.2f. Every window: %s.' % (mean(late) / mean(first),
                                                                       ', '.join(map(str, frames))))
    replace_section(os.path.join(ROOT, 'perf', 'README.md'), 'output_rate', text,
                    heading='## Output at every step')
    print(text)


if __name__ == '__main__':
    main()
