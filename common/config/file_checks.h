// Files that hold nothing a reader can use are refused before any parser sees them, with the
// file named. Parsers are too forgiving on their own: YAML takes an empty file for "all
// defaults" and random bytes for a scalar, and image decoders fill a JPEG or PNM that was cut
// off with grey or zero pixels. Saved state has its own framing (persist/atomic_file.h) and LCM
// logs their own check (importers/lcm_log_io.h).
#pragma once

#include <string>

namespace rgnav::config {

// The whole text of `path`. Throws ConfigError naming the file when it cannot be opened, is
// empty (no bytes, or only white space: "PATH: empty WHAT file"), or is not text (a NUL byte or
// invalid UTF-8: "PATH: not a WHAT file (binary data at byte N)"). `what` names the kind of
// file in the messages ("config", "launch config", ...).
std::string read_text_file(const std::string& path, const std::string& what);

// Why `text` is not text ("" when it is): the first NUL byte or invalid UTF-8 sequence.
std::string binary_defect(const std::string& text);

// The bytes of an image file that is whole, for cv::imdecode. Throws ConfigError naming the
// file when it cannot be opened, is empty, or is cut off: a PNG without its IEND chunk, a
// JPEG without its end-of-image marker, a binary PGM/PPM shorter than its header says. Other
// formats are passed on for the decoder to judge (a caller refuses what it cannot decode).
std::string read_image_file(const std::string& path, const std::string& what);

}  // namespace rgnav::config
