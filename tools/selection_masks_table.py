#!/usr/bin/env python3
"""The table of docs/results/selection_masks.md: object masks written from a selection
(`goris select ... --write-masks DIR --masks-iou`) against the generator's exact masks, on a run trained
WITHOUT masks, and the removal each set of masks drives, for
  masks      the selection voted by the exact masks themselves (`--masks`): what the mask writer loses; the
             removal is `goris select RUN --masks` (the exact masks)
  two-click  clicked once in each of two training views (`--click` twice, the default `--click-by region`):
             the pixel deepest inside the exact mask (farthest from its border), in the view with the
             largest mask and in the one with the largest mask among those at least a quarter of the views
             away; the removal is `goris select RUN --masks DIR` with the masks the two clicks wrote
Each removal runs on a copy of the same stage-1 run (`goris remove`, then `goris eval --split test`: PSNR and
ghost ratio in the changed region).

  tools/selection_masks_table.py --work DIR [--goris build/bin/goris] [--iters 2000] [--resolution 128]
                                 [--stage1 PATTERN] [--doc FILE] SCENE...

Stage 1 runs go to DIR/<scene>/run (reused when finished: its point_cloud.ply exists), or, with --stage1,
are the finished runs PATTERN names ({scene} replaced by the scene's folder name; e.g. a suite bench's
OUT/runs/{scene}/medium/stage1_default/run, what `goris train` gives by default, or stage1_radiance, the
radiance runs of its `baseline`). Such a run may have been trained with the object masks: in either mode they
teach only the label channel, whose gradients never reach the geometry (ImageGradients::extras_detached), so
its Gaussians are those of the same run without masks, and neither selection reads the label. The removals to
DIR/<scene>/<method>/run (reused when evaluated: removal/metrics.json exists); the table is printed on stdout
with paths relative to the current folder. Standard library only (PNG masks are decoded here).
"""
import argparse
import json
import os
import shutil
import struct
import subprocess
import sys
import zlib


def read_png_grey(path):
    """First channel of an 8-bit PNG (grey, grey+alpha, RGB or RGBA), as rows of ints."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG")
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            if depth != 8:
                raise SystemExit(f"{path}: {depth}-bit PNG (8-bit expected)")
            channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * channels
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([line[x * channels] for x in range(w)])
        prev = line
    return rows


def deepest_pixel(mask):
    """The set pixel (> 127) farthest from an unset one or the border (chessboard distance), and its area."""
    h, w = len(mask), len(mask[0])
    inside = [[mask[y][x] > 127 for x in range(w)] for y in range(h)]
    area = sum(map(sum, inside))
    best, frontier = None, inside
    while True:
        nxt = [[frontier[y][x] and 0 < x < w - 1 and 0 < y < h - 1 and all(
            frontier[y + dy][x + dx] for dy in (-1, 0, 1) for dx in (-1, 0, 1)) for x in range(w)] for y in range(h)]
        cells = [(y, x) for y in range(h) for x in range(w) if frontier[y][x]]
        if not cells:
            return best, area
        # The middle of what is left: the cell closest to its centroid.
        cy = sum(c[0] for c in cells) / len(cells)
        cx = sum(c[1] for c in cells) / len(cells)
        best = min(cells, key=lambda c: (c[0] - cy) ** 2 + (c[1] - cx) ** 2)
        frontier = nxt


def run(cmd, log):
    with open(log, "w") as f:
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        lines = open(log).read().strip().splitlines()
        # The error line (stderr, unbuffered) can come before the last of stdout's buffered lines.
        tail = [l for l in lines if l.startswith("error:")][-1:] or lines[-1:]
        print(f"{' '.join(cmd[:3])}... failed ({r.returncode}): {tail} (log {log})", file=sys.stderr)
        return False
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--work", required=True)
    ap.add_argument("--goris", default="build/bin/goris")
    ap.add_argument("--iters", type=int, default=2000)
    ap.add_argument("--resolution", type=int, default=128)
    ap.add_argument("--device", default="cpu")
    ap.add_argument("--stage1", help="finished stage-1 runs to use instead of training: a path with {scene}")
    ap.add_argument("--doc", default="docs/results/selection_masks.md",
                    help="the file the table is written for, named in its command line")
    a = ap.parse_args()
    rows = []
    for scene in a.scenes:
        name = os.path.basename(os.path.normpath(scene))
        work = os.path.abspath(os.path.join(a.work, name))
        run_dir = a.stage1.replace("{scene}", name) if a.stage1 else os.path.join(work, "run")
        os.makedirs(work, exist_ok=True)
        if a.stage1 and not os.path.exists(os.path.join(run_dir, "point_cloud.ply")):
            print(f"{name}: no finished stage-1 run at {run_dir}", file=sys.stderr)
            continue
        if not os.path.exists(os.path.join(run_dir, "point_cloud.ply")):
            if not run([a.goris, "train", scene, "--out", run_dir, "--iters", str(a.iters), "--resolution",
                        str(a.resolution), "--device", a.device, "--set", "use_object_masks=false"],
                       os.path.join(work, "train.log")):
                continue
        frames = json.load(open(os.path.join(scene, "transforms_train.json")))["frames"]
        views = [os.path.basename(f["file_path"]) for f in frames]
        picks = []
        for i, v in enumerate(views):
            m = os.path.join(scene, "train", "mask_" + v.split("_", 1)[1] + ".png")
            mask = read_png_grey(m)
            picks.append((i, v, mask))
        areas = [(sum(sum(p > 127 for p in row) for row in mask), i) for i, _, mask in picks]
        first = max(areas)[1]
        far = [x for x in areas if min(abs(x[1] - first), len(views) - abs(x[1] - first)) >= len(views) // 4]
        second = max(far)[1]
        clicks = []
        for k in (first, second):
            _, v, mask = picks[k]
            (y, x), _ = deepest_pixel(mask)
            s = a.resolution / len(mask[0])
            clicks += ["--click", v, str(int(x * s)), str(int(y * s))]
        row = {"scene": name, "clicks": " ".join(clicks)}
        for method, args in (("masks", ["--masks"]), ("two-click", clicks)):
            out = os.path.join(work, method)
            os.makedirs(out, exist_ok=True)
            ok = run([a.goris, "select", run_dir, *args, "--out", os.path.join(out, "selection.json"), "--previews",
                      "0", "--device", a.device, "--write-masks", os.path.join(out, "masks"), "--masks-iou"],
                     os.path.join(out, "select.log"))
            if not ok:
                continue
            iou = json.load(open(os.path.join(out, "masks", "iou.json")))
            sel = json.load(open(os.path.join(out, "selection.json")))
            row[method] = (iou["mean_iou"], iou["min_iou"], sel["selected"], sel["gaussian_count"])
            # The removal these masks drive, on a copy of the stage-1 run.
            rm_run = os.path.join(out, "run")
            metrics = os.path.join(rm_run, "removal", "metrics.json")
            if not os.path.exists(metrics):
                shutil.rmtree(rm_run, ignore_errors=True)
                shutil.copytree(run_dir, rm_run, ignore=shutil.ignore_patterns("removal", "selection*"))
                masks = ["--masks"] if method == "masks" else ["--masks", os.path.join(out, "masks")]
                if not (run([a.goris, "select", rm_run, *masks, "--previews", "1", "--device", a.device],
                            os.path.join(out, "select_masks.log")) and
                        run([a.goris, "remove", rm_run, "--device", a.device], os.path.join(out, "remove.log")) and
                        run([a.goris, "eval", os.path.join(rm_run, "removal"), "--split", "test", "--device",
                             a.device], os.path.join(out, "eval.log"))):
                    continue
            rem = json.load(open(metrics))["removal"]
            row[method + "-removal"] = (rem["region_psnr"], rem["ghost_ratio"])
        rows.append(row)

    print("# Object masks from a selection: IoU against the exact masks, and the removal they drive\n")
    opts = (f" --iters {a.iters}" if a.iters != 2000 and not a.stage1 else "") + (
        f" --resolution {a.resolution}" if a.resolution != 128 and not a.stage1 else "") + (
        f" --stage1 {a.stage1}" if a.stage1 else "") + (
        f" --doc {a.doc}" if a.doc != "docs/results/selection_masks.md" else "")
    stage1 = (f"stage 1: {a.iters} iterations at {a.resolution} px, trained without the object masks; " if not a.stage1
              else "stage 1: the runs --stage1 names, whose object masks teach only the label in either mode (its "
                   "gradients never reach the geometry, so the Gaussians are those of a run without masks; neither "
                   "selection reads the label); ")
    print("Written by `tools/selection_masks_table.py --work DIR" + opts + " " + " ".join(a.scenes) +
          " > " + a.doc + "` (SUITE: the generalization suite's rendered scenes, "
          "`goris bench pipeline --suite generalization --out BENCH`; " + stage1 +
          "`goris select ... --write-masks DIR --masks-iou` on every training view; the removal: "
          "`goris select RUN --masks [DIR]`, `goris remove`, `goris eval --split test` on a copy of the same run).\n")
    print("| scene | exact masks: mean / min IoU | two-click: mean / min IoU | two-click: selected / Gaussians | "
          "removal, exact masks: changed-region PSNR / ghost | removal, two-click masks: changed-region PSNR / ghost | "
          "two-click - exact (dB) | clicks |")
    print("|---|--:|--:|--:|--:|--:|--:|---|")
    for r in rows:
        cell = lambda k: f"{r[k][0]:.3f} / {r[k][1]:.3f}" if k in r else "failed"
        rcell = lambda k: f"{r[k][0]:.2f} dB / {r[k][1]:.3f}" if k in r else "failed"
        sel = f"{r['two-click'][2]} / {r['two-click'][3]}" if "two-click" in r else ""
        diff = (f"{r['two-click-removal'][0] - r['masks-removal'][0]:+.2f}"
                if "two-click-removal" in r and "masks-removal" in r else "")
        print(f"| {r['scene']} | {cell('masks')} | {cell('two-click')} | {sel} | {rcell('masks-removal')} | "
              f"{rcell('two-click-removal')} | {diff} | `{r['clicks']}` |")
    done = [r for r in rows if "two-click" in r]
    if done:
        print(f"\nMean over the {len(done)} scenes: IoU with the exact masks' selection "
              f"{sum(r['masks'][0] for r in done if 'masks' in r) / len(done):.3f}, two-click "
              f"{sum(r['two-click'][0] for r in done) / len(done):.3f} (worst scene "
              f"{min(r['two-click'][0] for r in done):.3f}); scenes where two-click reaches a mean IoU >= 0.9: "
              f"{sum(r['two-click'][0] >= 0.9 for r in done)} of {len(rows)}.")
    both = [r for r in rows if "two-click-removal" in r and "masks-removal" in r]
    if both:
        d = [r["two-click-removal"][0] - r["masks-removal"][0] for r in both]
        print(f"Removal: two-click minus exact masks, changed-region PSNR: mean {sum(d) / len(d):+.2f} dB, worst "
              f"{min(d):+.2f} dB; within 0.5 dB on {sum(x >= -0.5 for x in d)} of {len(both)} scenes.")
        good = [r["scene"] for r in both
                if r["two-click"][0] >= 0.9 and r["two-click-removal"][0] - r["masks-removal"][0] >= -0.5]
        print(f"Both (IoU >= 0.9 and the removal within 0.5 dB) on {len(good)} of {len(rows)} scenes"
              + (f": {', '.join(good)}." if good else "."))
    print("""
`exact masks` is the selection voted by the exact masks (`goris select --masks`): what the mask writer loses
on a selection that is about right. `two-click` is the default `--click-by region`: each click's region of
its view (median depth and photo colour on a tolerance ladder), lifted to the Gaussians by their rendered
weight in the clicked views, closed, then voted once more by every view's silhouette of the selection (the
selected Gaussians rendered alone, less the view's glossy pixels); with glossy masks, the clicks' regions
never enter glossy pixels and what lies beyond the glossy surface the target stands on (its reflection) is
left out at each step. The removal columns
drive `goris remove` with each set of masks on copies of the same stage-1 run (changed region: the pixels
where the test views with and without the target differ; ghost: what is left of the target there, 0 is
none). The variants that lost: docs/lab/2026-12-04-click-regions-and-mask-edges.md,
docs/lab/2026-12-05-intrinsic-suite-and-two-click-masks.md and docs/lab/2026-12-05-click-silhouettes-and-support-plane.md.""")

if __name__ == "__main__":
    main()
