#!/usr/bin/env python3
"""Half-size copy of a data set for the device carry (64 MiB): every PNG shrunk by 2x2 box averaging (what
OpenCV's area filter does for an exact halving, up to 8-bit rounding), other files copied. The copy is for
device-bundle/data/ (git-ignored), never for the repository.
Usage: half_size_dataset.py SRC_DATASET DST_FOLDER   (needs Pillow: apt-get install python3-pil)"""
import os
import shutil
import sys

try:
    from PIL import Image
except ImportError:
    sys.exit("half_size_dataset: Pillow is missing (apt-get install python3-pil)")

if len(sys.argv) != 3:
    sys.exit(__doc__)
src, dst = sys.argv[1], sys.argv[2]
if not os.path.isfile(os.path.join(src, "transforms_train.json")):
    sys.exit(f"half_size_dataset: {src}: no transforms_train.json (not a data set)")
for root, _, files in os.walk(src):
    out = os.path.join(dst, os.path.relpath(root, src))
    os.makedirs(out, exist_ok=True)
    for f in files:
        path = os.path.join(root, f)
        if f.lower().endswith(".png"):
            Image.open(path).reduce(2).save(os.path.join(out, f), optimize=True)
        else:
            shutil.copy(path, out)
