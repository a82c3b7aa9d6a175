#!/usr/bin/env python3
"""The IoU table of docs/results/selection_masks.md: object masks written from a selection
(`goris select ... --write-masks DIR --masks-iou`) against the generator's exact masks, on a run trained
WITHOUT masks, for
  masks      the selection voted by the exact masks themselves (`--masks`): what the mask writer loses, with
             the coverage masks as rendered (default) and moved onto the photo's edges (`--mask-edges photo`)
  two-click  clicked once in each of two training views (`--click` twice, the default `--click-by region`):
             the pixel deepest inside the exact mask (farthest from its border), in the view with the
             largest mask and in the one with the largest mask among those at least a quarter of the views away.

  tools/selection_masks_table.py --work DIR [--goris build/bin/goris] [--iters 2000] [--resolution 128] SCENE...

Stage 1 runs go to DIR/<scene>/run (reused when finished: its point_cloud.ply exists); the table is printed on
stdout. Standard library only (PNG masks are decoded here).
"""
import argparse
import json
import os
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
        tail = open(log).read().strip().splitlines()[-1:]
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
    a = ap.parse_args()
    rows = []
    for scene in a.scenes:
        name = os.path.basename(os.path.normpath(scene))
        work = os.path.abspath(os.path.join(a.work, name))
        run_dir = os.path.join(work, "run")
        os.makedirs(work, exist_ok=True)
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
        for method, args in (("masks", ["--masks"]), ("masks-photo", ["--masks", "--mask-edges", "photo"]),
                             ("two-click", clicks)):
            out = os.path.join(work, method)
            os.makedirs(out, exist_ok=True)
            ok = run([a.goris, "select", run_dir, *args, "--out", os.path.join(out, "selection.json"), "--previews",
                      "2", "--device", a.device, "--write-masks", os.path.join(out, "masks"), "--masks-iou"],
                     os.path.join(out, "select.log"))
            if ok:
                iou = json.load(open(os.path.join(out, "masks", "iou.json")))
                sel = json.load(open(os.path.join(out, "selection.json")))
                row[method] = (iou["mean_iou"], iou["min_iou"], sel["selected"], sel["gaussian_count"])
        rows.append(row)

    print("# Object masks from a selection: IoU against the exact masks\n")
    print("Written by `tools/selection_masks_table.py --work DIR " + " ".join(a.scenes) +
          f"` (stage 1: {a.iters} iterations at {a.resolution} px, trained without the object masks; "
          "`goris select ... --write-masks DIR --masks-iou` on every training view).\n")
    print("| scene | masks, coverage edges: mean / min IoU | masks, photo edges: mean / min IoU | "
          "two-click: mean / min IoU | two-click: selected / Gaussians | clicks |")
    print("|---|--:|--:|--:|--:|---|")
    for r in rows:
        cell = lambda k: f"{r[k][0]:.3f} / {r[k][1]:.3f}" if k in r else "failed"
        sel = f"{r['two-click'][2]} / {r['two-click'][3]}" if "two-click" in r else ""
        print(f"| {r['scene']} | {cell('masks')} | {cell('masks-photo')} | {cell('two-click')} | {sel} | "
              f"`{r['clicks']}` |")
    done = [r for r in rows if "two-click" in r]
    if done:
        print(f"\nMean over the {len(done)} scenes: masks (coverage edges) "
              f"{sum(r['masks'][0] for r in done if 'masks' in r) / len(done):.3f}, two-click "
              f"{sum(r['two-click'][0] for r in done) / len(done):.3f}; scenes where two-click reaches a mean IoU "
              f">= 0.9: {sum(r['two-click'][0] >= 0.9 for r in done)} of {len(rows)}.")


if __name__ == "__main__":
    main()
