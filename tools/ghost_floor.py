#!/usr/bin/env python3
"""Where a suite scene's ghost comes from: stage 1's own error against the photos with the target, next to
the ghost left after the removal, inside the changed region of every test view.

    tools/ghost_floor.py BENCH_OUT [--config default] [--schedule medium] [--work DIR] [--goris BIN] [SCENE ...]

`goris eval` reports the floor and the ghost of a removal folder itself (and the suite tables show them); this
script adds the share of the ghost inside the target's own mask. BENCH_OUT is a `goris bench pipeline --suite
...` output folder; the scenes' data sets are read from each
stage-1 run's config.json. Per scene (Markdown table on stdout):
  floor   sum |stage-1 render - full_| / sum |full_ - r_|: how far stage 1 itself is from the photos where
          the target changed them (a removal that reproduced r_ exactly through this model would still be off
          by about this much);
  ghost   sum |render after removal - r_| / sum |full_ - r_| (as goris eval, after a 3x3 median);
  inside  the part of the ghost inside the target's own mask (mask_XXX.png of the test views);
  unseen  the part of the ghost on surface points no training view saw: the test pixel's ray meets the removal's
          glossy plane (RUN/removal/report.json) at a point that no training view shows as glossy surface
          (gloss_XXX.png) and at least one shows covered by the target (mask_XXX.png). Only this part is beyond
          what the other views' photos hold; "-" without a glossy plane or the synthetic scenes' masks.
Needs numpy and OpenCV (Debian: python3-numpy python3-opencv).
"""
import argparse, glob, json, os, subprocess, tempfile
import cv2
import numpy as np


def load(path, background=(0.0, 0.0, 0.0)):
    """An image as goris eval sees it: RGBA composited on the run's background (the synthetic scenes' photos
    carry colour where their alpha is 0), quantised to 8 bits, then the 3x3 median."""
    im = cv2.imread(path, cv2.IMREAD_UNCHANGED)
    if im.ndim == 2:
        im = cv2.cvtColor(im, cv2.COLOR_GRAY2BGR)
    if im.shape[2] == 4:
        a = im[:, :, 3:].astype(np.float64) / 255.0
        bg = np.array(background[::-1], np.float64) * 255.0  # BGR
        im = np.round(im[:, :, :3] * a + bg * (1.0 - a)).astype(np.uint8)
    return cv2.medianBlur(im, 3)[:, :, ::-1].astype(np.float64) / 255.0


def changed_region(full, after):
    """goris eval's changed region of two loaded images: any channel differs by more than 0.04, dilated 2 px."""
    return cv2.dilate((np.abs(full - after).max(axis=2) > 0.04).astype(np.uint8), np.ones((5, 5), np.uint8)) > 0


def nerf_cameras(data, split):
    """transforms_SPLIT.json: its frames as (name, camera-to-world 4x4 in the Blender convention), the focal
    length in pixels, and the images' width and height."""
    t = json.load(open(os.path.join(data, 'transforms_%s.json' % split)))
    first = cv2.imread(os.path.join(data, t['frames'][0]['file_path'] + '.png'), cv2.IMREAD_UNCHANGED)
    h, w = first.shape[:2]
    f = 0.5 * w / np.tan(0.5 * t['camera_angle_x'])
    return [(os.path.basename(fr['file_path']), np.array(fr['transform_matrix'], np.float64)) for fr in t['frames']], f, w, h


def unseen_surface(data, plane):
    """Per test view name: [H][W] bool, the pixels whose ray meets the plane (normal, offset) at a point that no
    training view shows as glossy surface while at least one shows the target over it; None without masks."""
    train, f, w, h = nerf_cameras(data, 'train')
    test = nerf_cameras(data, 'test')[0]
    views = []  # per training view: world-to-camera, its glossy surface, the target
    for name, c2w in train:
        k = name[2:]
        g = cv2.imread(os.path.join(data, 'train', 'gloss_%s.png' % k), cv2.IMREAD_GRAYSCALE)
        m = cv2.imread(os.path.join(data, 'train', 'mask_%s.png' % k), cv2.IMREAD_GRAYSCALE)
        if g is None or m is None:
            return None
        views.append((np.linalg.inv(c2w), g > 127, m > 127))
    n, off = np.array(plane['normal'], np.float64), float(plane['offset'])
    y, x = np.mgrid[0:h, 0:w] + 0.5
    cam_dirs = np.stack([(x - w / 2) / f, -(y - h / 2) / f, -np.ones_like(x)], -1)  # Blender: -z forward, y up
    out = {}
    for name, c2w in test:
        o, d = c2w[:3, 3], cam_dirs @ c2w[:3, :3].T
        with np.errstate(divide='ignore', invalid='ignore'):
            t = (off - o @ n) / (d @ n)
        t[~np.isfinite(t)] = -1.0  # parallel to the plane: no point
        X = o + t[..., None] * d
        seen, covered = np.zeros((h, w), bool), np.zeros((h, w), bool)
        for w2c, gloss, target in views:
            Xc = X @ w2c[:3, :3].T + w2c[:3, 3]
            z = -Xc[..., 2]
            u = np.floor(Xc[..., 0] / np.maximum(z, 1e-9) * f + w / 2).astype(int)
            v = np.floor(-Xc[..., 1] / np.maximum(z, 1e-9) * f + h / 2).astype(int)
            inside = (t > 0) & (z > 1e-9) & (u >= 0) & (v >= 0) & (u < w) & (v < h)
            uu, vv = np.clip(u, 0, w - 1), np.clip(v, 0, h - 1)
            seen |= inside & gloss[vv, uu]
            covered |= inside & target[vv, uu]
        out[name] = covered & ~seen
    return out


def render(goris, run, out):
    if not os.path.isdir(out):
        os.makedirs(os.path.dirname(out), exist_ok=True)
        subprocess.run([goris, 'render', run, '--split', 'test', '--out', out, '--device', 'cpu'], check=True,
                       capture_output=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('bench')
    ap.add_argument('scenes', nargs='*')
    ap.add_argument('--config', default='default')
    ap.add_argument('--schedule', default='medium')
    ap.add_argument('--work', default=None, help='where the renders go (default: a temporary folder, removed after)')
    ap.add_argument('--goris', default=os.path.join(os.path.dirname(__file__), '..', 'build', 'bin', 'goris'))
    return in_work_folder(ap.parse_intermixed_args(), table, 'ghost_floor_')


def in_work_folder(a, fn, prefix):
    """fn(a) with a.work set: the folder given, or a temporary one removed afterwards."""
    if a.work is None:
        with tempfile.TemporaryDirectory(prefix=prefix) as work:
            a.work = work
            return fn(a)
    return fn(a)


def table(a):
    runs = os.path.join(a.bench, 'runs')
    scenes = a.scenes or sorted(os.listdir(runs))
    print('| scene | floor (stage 1) | ghost after removal | of it inside the target | of it where no view saw the surface |')
    print('|---|--:|--:|--:|--:|')
    for s in scenes:
        base = os.path.join(runs, s, a.schedule)
        run = os.path.join(base, a.config, 'run')
        if not os.path.isdir(os.path.join(run, 'removal')):
            continue
        config = json.load(open(os.path.join(run, 'config.json')))
        test, bg = os.path.join(config['data'], 'test'), config.get('background', [0.0, 0.0, 0.0])
        s1 = os.path.join(a.work, s + '_stage1')
        rm = os.path.join(a.work, s + '_removed')
        render(a.goris, run, s1)
        render(a.goris, os.path.join(run, 'removal'), rm)
        plane = json.load(open(os.path.join(run, 'removal', 'report.json'))).get('glossy_plane', {})
        unseen_px = unseen_surface(config['data'], plane) if 'normal' in plane else None
        floor = imprint = ghost = inside = unseen = 0.0
        for full_path in sorted(glob.glob(os.path.join(test, 'full_*.png'))):
            k = full_path[-7:-4]
            full, after = load(full_path, bg), load(os.path.join(test, 'r_%s.png' % k), bg)
            region = changed_region(full, after)
            mask = cv2.imread(os.path.join(test, 'mask_%s.png' % k), cv2.IMREAD_GRAYSCALE) > 127
            before_model, after_model = load(os.path.join(s1, 'r_%s.png' % k)), load(os.path.join(rm, 'r_%s.png' % k))
            imprint += np.abs(full - after)[region].sum()
            floor += np.abs(before_model - full)[region].sum()
            e = np.abs(after_model - after)
            ghost += e[region].sum()
            inside += e[region & mask].sum()
            if unseen_px is not None:
                unseen += e[region & unseen_px['r_%s' % k]].sum()
        unseen_cell = '%.2f' % (unseen / imprint) if unseen_px is not None else '-'
        print('| %s | %.2f | %.2f | %.2f | %s |' % (s, floor / imprint, ghost / imprint, inside / imprint, unseen_cell),
              flush=True)


if __name__ == '__main__':
    main()
