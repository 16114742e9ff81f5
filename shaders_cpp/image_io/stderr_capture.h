// Image codecs that print to stderr themselves (libpng's "libpng error: ..." through OpenImageIO)
// would put a second line before Tessera's one-line error. While a StderrCapture lives, file
// descriptor 2 goes to a temporary file; text() returns what was written, and the destructor restores
// stderr. Process-wide: use it around single-threaded decoding only (map loading, image diffs), never
// around a draw whose threads might log.
#pragma once

#include <cstdio>
#include <string>

#include <unistd.h>

namespace tessera {

class StderrCapture {
 public:
  StderrCapture() {
    std::fflush(stderr);
    file_ = std::tmpfile();
    if (!file_) return;
    saved_ = ::dup(2);
    if (saved_ < 0 || ::dup2(::fileno(file_), 2) < 0) {
      if (saved_ >= 0) ::close(saved_);
      saved_ = -1;
    }
  }
  ~StderrCapture() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      ::dup2(saved_, 2);
      ::close(saved_);
    }
    if (file_) std::fclose(file_);
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  // What was written so far (at most the first 4 KB), line breaks kept.
  std::string text() const {
    if (!file_) return {};
    std::fflush(stderr);
    std::string out(4096, '\0');
    std::rewind(file_);
    out.resize(std::fread(out.data(), 1, out.size(), file_));
    std::fseek(file_, 0, SEEK_END);
    return out;
  }

 private:
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

}  // namespace tessera
