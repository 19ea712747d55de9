#include "importers/line_reader.h"

#include <stdexcept>

namespace rgnav::importers {

LineReader::LineReader(const std::string& path)
{
  file_ = gzopen(path.c_str(), "rb");
  if (!file_) throw std::runtime_error("cannot open " + path);
  gzbuffer(file_, 1 << 17);
}

LineReader::~LineReader()
{
  if (file_) gzclose(file_);
}

bool LineReader::next(std::string* line)
{
  line->clear();
  if (!error_.empty()) return false;
  char buf[8192];
  bool got_any = false;
  for (;;) {
    if (!gzgets(file_, buf, sizeof buf)) break;
    got_any = true;
    line->append(buf);
    if (!line->empty() && line->back() == '\n') break;
  }
  int errnum = Z_OK;
  const char* msg = gzerror(file_, &errnum);
  // Z_BUF_ERROR at the end means the compressed stream stopped mid-way: a truncated file.
  if (errnum != Z_OK && errnum != Z_STREAM_END) {
    error_ = errnum == Z_BUF_ERROR ? "unexpected end of compressed data (truncated file)"
                                   : std::string("read error: ") + (msg ? msg : "?");
    // The partial last line of a truncated stream is not trusted.
    return false;
  }
  if (!got_any) return false;
  while (!line->empty() && (line->back() == '\n' || line->back() == '\r')) line->pop_back();
  ++line_number_;
  return true;
}

}  // namespace rgnav::importers
