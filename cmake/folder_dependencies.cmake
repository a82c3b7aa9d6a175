# Which folders each folder of the engine, the editor and the programs may include from (besides itself,
# the standard library and third-party headers). Checked on every build by check_folder_dependencies.cmake:
# an #include of an undeclared folder, a cycle in this table, or a cycle between the top-level folders it
# implies fails the build. A folder is two levels deep: core/io, train/loop, ui/document, tools/synth,
# app/goris (deeper folders, such as train/loop/hooks, belong to theirs).
#
# Keep it acyclic and pointing downwards. Each top-level folder of the engine is one concept and one library
# (the top CMakeLists.txt): core (the foundation: compute, I/O, the scene, capture, 2D inpainting, metrics)
# <- render (rasterizing, tracing, shading) <- train (training) <- removal (object removal) and export (`goris
# export`), which stand side by side. Over them: app -> ui, and app -> tools -> core (the code of the
# benchmarks and of `goris synth`, which the engine and the editor never include).
# Inside train/, from the bottom: optimizer (Adam, densification) and losses, config, loop (the trainer, its
# checkpoints and hooks), run (a run's folder and inputs), radiance and intrinsic (the differentiable
# renderers), setup (a run's renderer, mode and trainer). Inside removal/: selection, masks, shadow, lift,
# pipeline. Inside export/: frames, distill, run.
# Inside ui/, from the bottom: gl, display (frames to pixels), selection, document (AppState), viewport,
# panels, script, shell. Inside app/, the `goris` program's user commands (app/goris) and its benchmarks
# (app/bench) stand side by side, neither including the other, over what every command shares
# (app/cli_common).
set(GORIS_FOLDER_DEPENDENCIES
  "core/util:"
  "core/compute:core/util"
  "core/io:core/compute core/util"
  "core/scene:core/compute core/io core/util"
  "core/capture:core/io core/util"
  "core/inpaint:core/io core/util"
  "core/metrics:core/compute core/io core/util"
  "render/math:core/compute"
  "render/envmap:core/compute core/util"
  "render/raster:core/compute core/io core/scene core/util render/math"
  "render/trace:core/compute core/scene core/util render/math render/raster"
  "render/shading:core/compute core/io core/util render/envmap render/raster"
  "render/ssf:core/compute core/util"
  "render/maps:core/io"
  "train/optimizer:core/compute core/scene core/util"
  "train/losses:core/io"
  "train/config:core/compute core/io core/util train/optimizer"
  "train/loop:core/compute core/io core/scene core/util train/config train/losses train/optimizer"
  "train/run:core/io core/scene core/util train/config train/loop"
  "train/radiance:core/compute core/io core/scene render/raster train/config train/loop train/losses"
  "train/intrinsic:core/compute core/io core/scene core/util render/envmap render/raster render/shading render/ssf render/trace train/config train/loop train/optimizer train/radiance"
  "train/setup:core/compute core/io core/scene core/util render/raster train/config train/intrinsic train/loop train/radiance train/run"
  "removal/selection:core/inpaint core/io core/scene core/util render/raster render/trace"
  "removal/masks:core/inpaint core/io core/scene core/util removal/selection render/raster train/loop"
  "removal/shadow:core/io core/scene core/util removal/masks render/raster render/trace train/loop"
  "removal/lift:core/compute core/inpaint core/io core/scene core/util removal/masks removal/selection render/maps render/raster train/intrinsic train/loop train/run"
  "removal/pipeline:core/compute core/inpaint core/io core/scene core/util removal/lift removal/masks removal/selection removal/shadow render/raster train/intrinsic train/loop train/radiance train/run train/setup"
  "export/frames:core/io core/scene core/util render/maps render/raster train/intrinsic"
  "export/distill:core/compute core/io core/scene core/util export/frames train/config train/loop train/losses train/radiance"
  "export/run:core/compute core/io core/scene core/util export/distill export/frames render/maps render/raster train/config train/loop train/losses train/radiance train/run train/setup"
  "tools/report:core/util"
  "tools/synth:core/util"
  "ui/gl:core/compute core/util"
  "ui/display:core/compute core/io core/scene core/util render/maps render/raster train/config train/intrinsic ui/gl"
  "ui/selection:core/inpaint core/io core/scene core/util removal/selection render/raster ui/display"
  "ui/document:core/capture core/compute core/io core/scene core/util export/run removal/pipeline render/maps train/config train/loop train/radiance train/run train/setup ui/display ui/selection"
  "ui/viewport:core/util ui/display ui/document ui/gl"
  "ui/panels:core/capture core/compute core/io core/util train/config ui/document ui/gl ui/viewport"
  "ui/script:core/util render/maps ui/document ui/panels ui/selection ui/viewport"
  "ui/shell:core/io core/util ui/display ui/document ui/gl ui/panels ui/script ui/viewport"
  "app/studio:core/util ui/shell"
  "app/cli_common:core/compute core/util"
  "app/goris:app/cli_common core/capture core/compute core/inpaint core/io core/metrics core/scene core/util export/run removal/pipeline removal/selection render/maps render/raster tools/synth train/config train/intrinsic train/loop train/losses train/radiance train/run train/setup"
  "app/bench:app/cli_common core/compute core/io core/util removal/pipeline render/raster render/trace tools/report tools/synth train/config train/intrinsic train/losses train/run train/setup"
)
