# Which folders each folder of the engine, the editor and the programs may include from (besides itself,
# the standard library and third-party headers). Checked on every build by check_folder_dependencies.cmake:
# an #include of an undeclared folder, or a cycle in this table, fails the build. A folder is two levels
# deep: core/io, render/train, ui/document, tools/synth, app/goris.
#
# Keep it acyclic and pointing downwards: app -> ui -> render -> core, and app -> tools -> core (the code of
# the benchmarks and of `goris synth`, which the engine and the editor never include). Inside ui/, from the
# bottom: gl, display (frames to pixels), selection, document (AppState), viewport, panels, script, shell.
# Inside app/, the `goris` program's user commands (app/goris) and its benchmarks (app/bench) stand side by
# side, neither including the other, over what every command shares (app/cli_common).
set(GORIS_FOLDER_DEPENDENCIES
  "core/util:"
  "core/compute:core/util"
  "core/io:core/compute core/util"
  "core/scene:core/compute core/io core/util"
  "core/capture:core/io core/util"
  "core/inpaint:core/io core/util"
  "core/metrics:core/compute core/io core/util"
  "core/removal:core/io core/scene core/util"
  "core/train:core/compute core/io core/removal core/scene core/util"
  "render/math:core/compute"
  "render/envmap:core/compute core/util"
  "render/raster:core/compute core/io core/scene core/util render/math"
  "render/trace:core/compute core/scene core/util render/math render/raster"
  "render/shading:core/compute core/io core/util render/envmap render/raster"
  "render/ssf:core/compute core/train core/util"
  "render/intrinsic:core/compute core/train core/util render/shading render/ssf"
  "render/train:core/compute core/io core/scene core/train core/util render/envmap render/intrinsic render/raster render/shading render/ssf render/trace"
  "render/maps:core/io core/scene core/util render/raster render/train"
  "render/export:core/compute core/io core/scene core/train core/util render/maps render/raster render/train"
  "render/removal:core/compute core/inpaint core/io core/removal core/scene core/train core/util render/maps render/raster render/trace render/train"
  "tools/report:core/util"
  "tools/synth:core/util"
  "ui/gl:core/compute core/util"
  "ui/display:core/compute core/io core/removal core/scene core/train core/util render/maps render/raster render/train ui/gl"
  "ui/selection:core/inpaint core/io core/removal core/scene core/util render/raster render/removal ui/display"
  "ui/document:core/capture core/compute core/io core/removal core/train core/util render/export render/maps render/removal render/train ui/display ui/selection"
  "ui/viewport:core/util ui/display ui/document ui/gl"
  "ui/panels:core/capture core/compute core/io core/train core/util ui/document ui/gl ui/viewport"
  "ui/script:core/util render/maps ui/document ui/panels ui/selection ui/viewport"
  "ui/shell:core/io core/util ui/display ui/document ui/gl ui/panels ui/script ui/viewport"
  "app/studio:core/util ui/shell"
  "app/cli_common:core/compute core/util"
  "app/goris:app/cli_common core/capture core/compute core/inpaint core/io core/metrics core/removal core/scene core/train core/util render/export render/maps render/raster render/removal render/train tools/synth"
  "app/bench:app/cli_common core/compute core/io core/train core/util render/raster render/removal render/trace render/train tools/report tools/synth"
)
