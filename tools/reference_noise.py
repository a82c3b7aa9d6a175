#!/usr/bin/env python3
"""What the test references' own path-tracing noise costs a suite's ghost: the first test views rendered again
with Blender at more samples per pixel and another seed, and the ghost measured against both.

    tools/reference_noise.py BENCH_OUT [--spp 512] [--views 4] [--configs default] [--schedule medium]
                             [--work DIR] [--goris BIN] [--blender BIN] [SCENE ...]

BENCH_OUT is a `goris bench pipeline --suite ...` output folder; each scene's data set (its scene.json from
`goris synth`) is read from the stage-1 run's config.json. Per scene, over the first --views test views
(Markdown table on stdout; every sum over the changed region and 3 channels after the 3x3 median, as goris eval):
  noise    sum |clean r_ - r_| / sum |full_ - r_|: the ghost of a removal that rendered the scene without the
           target exactly and without noise, against the suite's references: the least any removal can score;
  ghost    per configuration, sum |render - r_| / sum |full_ - r_| (the suite's references), then the same
           against the clean references (sum |render - clean r_| / sum |clean full_ - clean r_|, the changed
           region taken from the clean pair);
  floor    per configuration, the same two for its stage 1's own render against full_ (tools/ghost_floor.py).
With --work the renders stay there and are reused by a later call (the runs' renders whenever present, the
clean references when rendered from the same description).
Blender renders 2 x views images per scene at --spp (about a minute per scene at 512 spp, 128 px, 2 cores).
Needs numpy, OpenCV and Blender (Debian: python3-numpy python3-opencv blender).
"""
import argparse, json, os, shutil, subprocess, sys
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ghost_floor import changed_region, in_work_folder, load, render  # noqa: E402  (one loader and renderer for both tools)

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'resources', 'synth', 'render_scene.py')


def clean_references(data, out, spp, views, blender):
    """Renders the first `views` test views of the data set's scene.json at `spp` with another seed into
    out/test; returns how many. A folder rendered from the same description is reused, any other replaced."""
    desc = json.load(open(os.path.join(data, 'scene.json')))
    desc['render']['spp'] = spp
    desc['render']['seed'] = desc['render']['seed'] + 1
    desc['cameras']['test'] = desc['cameras']['test'][:views]
    desc['ground_truth_maps'] = False
    n = len(desc['cameras']['test'])
    record = os.path.join(out, 'scene.json')
    done = [os.path.join(out, 'test', '%s_%03d.png' % (k, i)) for i in range(n) for k in ('full', 'r')]
    if os.path.isfile(record) and json.load(open(record)) == desc and all(map(os.path.isfile, done)):
        return n
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    with open(record + '.part', 'w') as f:  # the record last: an interrupted render is not reused
        json.dump(desc, f)
    with open(os.path.join(out, 'blender.log'), 'w') as log:
        r = subprocess.run([blender, '-b', '--factory-startup', '--python', SCRIPT, '--', record + '.part', out,
                            'test-only'], stdout=log, stderr=subprocess.STDOUT)
    if r.returncode != 0 or not all(map(os.path.isfile, done)):
        sys.exit('%s: Blender failed to render the test views again (exit %d); its log: %s'
                 % (data, r.returncode, os.path.join(out, 'blender.log')))
    os.replace(record + '.part', record)
    return n


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('bench')
    ap.add_argument('scenes', nargs='*')
    ap.add_argument('--spp', type=int, default=512)
    ap.add_argument('--views', type=int, default=4)
    ap.add_argument('--configs', default='default', help='comma-separated configurations of the bench')
    ap.add_argument('--schedule', default='medium')
    ap.add_argument('--work', default=None, help='where the renders go (default: a temporary folder, removed after)')
    ap.add_argument('--goris', default=os.path.join(os.path.dirname(__file__), '..', 'build', 'bin', 'goris'))
    ap.add_argument('--blender', default='blender')
    a = ap.parse_intermixed_args()
    if a.views < 1 or a.spp < 1:
        ap.error('--views and --spp must be at least 1')
    return in_work_folder(a, table, 'reference_noise_')


def table(a):
    runs = os.path.join(a.bench, 'runs')
    if not os.path.isdir(runs):
        sys.exit('%s: no runs/ folder (expected a `goris bench pipeline --suite` output)' % a.bench)
    configs = [c for c in a.configs.split(',') if c]
    scenes = a.scenes or sorted(os.listdir(runs))
    print('| scene | noise |' + ''.join(' %s ghost: suite refs / clean | %s floor: suite refs / clean |' % (c, c) for c in configs))
    print('|---|--:|' + '--:|--:|' * len(configs))
    for s in scenes:
        base = os.path.join(runs, s, a.schedule)
        present = [c for c in configs if os.path.isdir(os.path.join(base, c, 'run', 'removal'))]
        if not present:
            continue
        config = json.load(open(os.path.join(base, present[0], 'run', 'config.json')))
        data, bg = config['data'], config.get('background', [0.0, 0.0, 0.0])
        clean = os.path.join(a.work, s + '_clean')
        views = clean_references(data, clean, a.spp, a.views, a.blender)
        for c in present:
            render(a.goris, os.path.join(base, c, 'run'), os.path.join(a.work, s + '_' + c + '_stage1'))
            render(a.goris, os.path.join(base, c, 'run', 'removal'), os.path.join(a.work, s + '_' + c))
        sums = {}  # name -> [numerator, denominator]

        def add(name, num, den):
            acc = sums.setdefault(name, [0.0, 0.0])
            acc[0] += num
            acc[1] += den

        for k in range(views):
            v = '%03d' % k
            ref = lambda folder, name: load(os.path.join(folder, 'test', '%s_%s.png' % (name, v)), bg)
            full, after = ref(data, 'full'), ref(data, 'r')
            cfull, cafter = ref(clean, 'full'), ref(clean, 'r')
            reg, creg = changed_region(full, after), changed_region(cfull, cafter)
            imprint, cimprint = np.abs(full - after)[reg].sum(), np.abs(cfull - cafter)[creg].sum()
            add('noise', np.abs(cafter - after)[reg].sum(), imprint)
            for c in present:
                s1 = load(os.path.join(a.work, s + '_' + c + '_stage1', 'r_%s.png' % v))
                add(c + ' floor', np.abs(s1 - full)[reg].sum(), imprint)
                add(c + ' floor clean', np.abs(s1 - cfull)[creg].sum(), cimprint)
                rm = load(os.path.join(a.work, s + '_' + c, 'r_%s.png' % v))
                add(c, np.abs(rm - after)[reg].sum(), imprint)
                add(c + ' clean', np.abs(rm - cafter)[creg].sum(), cimprint)
        r = lambda name: sums[name][0] / sums[name][1] if name in sums and sums[name][1] > 0 else float('nan')
        pair = lambda name: '%.2f / %.2f' % (r(name), r(name + ' clean'))
        cells = ''.join(' %s | %s |' % (pair(c), pair(c + ' floor')) if c in present else ' - | - |' for c in configs)
        print('| %s | %.2f |%s' % (s, r('noise'), cells), flush=True)


if __name__ == '__main__':
    main()
