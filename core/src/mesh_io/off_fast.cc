// SPDX-License-Identifier: AGPL-3.0-or-later
#include "mesh_io/off_fast.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <vector>

namespace dot {
namespace {

// A read-only mapping of a file whose pages are given back as the parse
// passes them, so reading a scan does not hold the file in memory too.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    struct stat st;
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
      size_ = static_cast<size_t>(st.st_size);
      void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
      if (p != MAP_FAILED) {
        data_ = static_cast<const char*>(p);
        ::madvise(p, size_, MADV_SEQUENTIAL);
      }
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  const char* data() const { return data_; }
  size_t size() const { return size_; }
  // Drops the pages wholly before `p` from memory (they are not read again).
  void Release(const char* p) {
    constexpr size_t kStep = size_t{32} << 20;
    const auto page = static_cast<size_t>(::sysconf(_SC_PAGESIZE));
    const size_t upto = static_cast<size_t>(p - data_) / page * page;
    if (upto >= released_ + kStep) {
      ::madvise(const_cast<char*>(data_) + released_, upto - released_,
                MADV_DONTNEED);
      released_ = upto;
    }
  }

 private:
  const char* data_ = nullptr;
  size_t size_ = 0, released_ = 0;
};

class Parser {
 public:
  Parser(const char* p, const char* end) : p_(p), end_(end) {}
  const char* at() const { return p_; }

  // Whitespace, newlines and comments.
  void SkipSpace() {
    while (p_ < end_) {
      if (*p_ == '#') {
        while (p_ < end_ && *p_ != '\n') ++p_;
      } else if (*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\n') {
        ++p_;
      } else {
        return;
      }
    }
  }
  // Spaces within a line.
  void SkipBlanks() {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r')) ++p_;
  }
  // Whether the line ends here (only blanks or a comment left on it).
  bool AtLineEnd() {
    SkipBlanks();
    return p_ == end_ || *p_ == '\n' || *p_ == '#';
  }
  template <typename T>
  bool Number(T* out) {
    SkipBlanks();
    const auto r = std::from_chars(p_, end_, *out);
    if (r.ec != std::errc() || r.ptr == p_) return false;
    p_ = r.ptr;
    return p_ == end_ || *p_ == ' ' || *p_ == '\t' || *p_ == '\r' ||
           *p_ == '\n' || *p_ == '#';
  }
  bool Word(const char* w) {
    const char* q = p_;
    for (; *w != '\0'; ++w, ++q) {
      if (q == end_ || *q != *w) return false;
    }
    if (q != end_ && *q != ' ' && *q != '\t' && *q != '\r' && *q != '\n' &&
        *q != '#') {
      return false;
    }
    p_ = q;
    return true;
  }

 private:
  const char* p_;
  const char* end_;
};

bool Parse(MappedFile* file, PolygonSoup* out) {
  Parser in(file->data(), file->data() + file->size());
  const uint64_t bytes = file->size();
  in.SkipSpace();
  if (!in.Word("OFF")) return false;
  in.SkipSpace();
  uint64_t nv = 0, nf = 0, ne = 0;
  if (!in.Number(&nv) || !in.Number(&nf) || !in.Number(&ne)) return false;
  if (!in.AtLineEnd() || nv > bytes || nf > bytes || nv > INT32_MAX) {
    return false;
  }
  out->vertices.resize(nv);
  for (Vec3& v : out->vertices) {
    in.SkipSpace();
    if (!in.Number(&v.x) || !in.Number(&v.y) || !in.Number(&v.z) ||
        !in.AtLineEnd() || !std::isfinite(v.x) || !std::isfinite(v.y) ||
        !std::isfinite(v.z)) {
      return false;
    }
    file->Release(in.at());
  }
  out->faces.reserve(nf);
  std::vector<int32_t> face;
  for (uint64_t f = 0; f < nf; ++f) {
    in.SkipSpace();
    uint64_t n = 0;
    if (!in.Number(&n) || n < 3 || n > bytes) return false;
    face.resize(n);
    for (int32_t& c : face) {
      uint64_t v = 0;
      if (!in.Number(&v) || v >= nv) return false;
      c = static_cast<int32_t>(v);
    }
    if (!in.AtLineEnd()) return false;  // face colours: the careful path
    out->faces.Add(face.begin(), face.end());
    file->Release(in.at());
  }
  return true;
}

}  // namespace

bool ReadPlainOffFast(const std::string& path, PolygonSoup* out) {
  MappedFile file(path);
  if (file.data() == nullptr) return false;
  if (Parse(&file, out)) return true;
  *out = {};
  return false;
}

}  // namespace dot
