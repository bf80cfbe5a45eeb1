#pragma once
// Splicing: joining blocks of G-code onto a stream at layer boundaries so
// that the printer cannot tell (background.md §1: continue with a re-sliced
// file, swap, skip and repeat layers). gc-swap-layer, gc-relayer and
// gc-send's live swap rest on it. One piece per header; this one brings all:
//
//   splice_block.hpp    SpliceBlock: what to print (bytes of a file, how the
//                       machine stands at their start, a Z shift, an
//                       extrusion factor), from a LayerIndex or from a layer
//                       of the main stream itself (--repeat);
//   block_stream.hpp    BlockStream: prints one block, the seam (seam.hpp)
//                       first, pull style, to a SpliceSink;
//   splice_rewrite.hpp  SpliceRewrite: a line's Z shifted, E in the output's
//                       mode and coordinate, extrusion scaled;
//   splice_stage.hpp    SpliceStage: the pipeline stage over the main stream,
//                       asking a SplicePlan at every layer what happens.
#include "gcode/transform/block_stream.hpp"
#include "gcode/transform/splice_block.hpp"
#include "gcode/transform/splice_rewrite.hpp"
#include "gcode/transform/splice_stage.hpp"
