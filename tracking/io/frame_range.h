#pragma once
// `--frames A:B`: frames A .. B-1 of any source, by position in the source's frame order
// (0-based; `A:` to the end, `:B` from the start). One FrameSource wrapper, so the selection
// works the same for folders, multi-page TIFF, .cine and video. Frames keep their original
// index and name: a track of frames 100:200 says frame 100 for the first row.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "tracking/io/frame_source.h"

namespace dimer::tracking {

struct FrameRange {
  size_t first = 0;
  std::optional<size_t> end;  // one past the last; none: to the end of the source
  bool all() const { return first == 0 && !end; }
  std::string ToString() const;  // "A:B", "A:", ":B"
};

// Parses "A:B", "A:", ":B" (or "" for all frames). Throws UsageError naming --frames and the
// text when it is not two non-negative integers with B > A.
FrameRange ParseFrameRange(const std::string& text);

// The frames of `source` in `range`. Throws InputError naming `input` when the range starts at
// or beyond the last frame of a source that knows its length. An end beyond the last frame is
// cut to it.
std::unique_ptr<FrameSource> SelectFrames(std::unique_ptr<FrameSource> source,
                                          const FrameRange& range, const std::string& input);

}  // namespace dimer::tracking
