#pragma once
/// \file PovBench.h
/// `mvcl-bench pov`: a scene, loaded and framed exactly as mvcl-render loads and frames it, written
/// as a POV-Ray 3.7 scene (PovScene.h), and the mvcl-render camera options that give the same view.
/// `mvcl-bench image-diff`: how far apart two 8-bit images are, in levels (for checking that the
/// two renderers drew the same picture). scripts/frame-vs-povray.sh uses both.

namespace mvcl::bench {

/// argv[0] is "pov"; the rest are its options. Returns the process exit code.
int runPovExport(int argc, char **argv);

/// argv[0] is "image-diff"; the rest are its options. Returns the process exit code.
int runImageDiff(int argc, char **argv);

} // namespace mvcl::bench
