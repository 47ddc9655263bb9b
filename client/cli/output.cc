// SPDX-License-Identifier: AGPL-3.0-or-later
#include "cli/output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <streambuf>

#include "cli/inputs.h"

namespace dot::client {
namespace {

namespace fs = std::filesystem;

std::string LowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  if (!ext.empty()) ext = ext.substr(1);
  for (char& c : ext) c = static_cast<char>(std::tolower(c));
  return ext;
}

bool IsMeshFormat(const std::string& f) {
  return f == "obj" || f == "ply" || f == "off" || f == "stl";
}

std::string CannotWrite(const std::string& path, int error) {
  return "cannot write '" + path + "': " + std::strerror(error);
}

}  // namespace

bool NamesMeshFile(const std::string& path) {
  return IsMeshFormat(LowerExtension(path));
}

bool SameFile(const std::string& a, const std::string& b) {
  if (a == "-" || b == "-") return false;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    return fs::equivalent(a, b, ec);
  }
  const fs::path x = fs::weakly_canonical(fs::absolute(a, ec), ec);
  if (ec) return false;
  const fs::path y = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return !ec && x == y;
}

OutputTarget ResolveOutput(const std::string& input, const std::string& output,
                           const std::string& format, bool into_directory,
                           const OutputDefaults& defaults) {
  OutputTarget t;
  if (output == "-" || (output.empty() && IsStreamInput(input))) {
    t.to_stdout = true;
    t.format = format.empty() ? defaults.stdout_format : format;
    return t;
  }
  const std::string fmt = format.empty() ? defaults.file_format : format;
  const std::string stem =
      input == "-" ? "stdin" : fs::path(input).stem().string();
  std::error_code ec;
  if (output.empty()) {
    t.format = fmt;
    t.path = (fs::path(input).parent_path() /
              (stem + "." + defaults.suffix + "." + fmt))
                 .string();
  } else if (into_directory || output.back() == '/' ||
             fs::is_directory(output, ec)) {
    t.format = fmt;
    t.path = (fs::path(output) / (stem + "." + fmt)).string();
  } else {
    t.path = output;
    const std::string ext = LowerExtension(output);
    if (IsMeshFormat(ext)) {
      if (!format.empty() && format != ext) {
        t.error = "-o '" + output + "' names a ." + ext + " file but " +
                  defaults.format_flag + " says " + format;
      }
      t.format = ext;
    } else if (!format.empty()) {
      t.format = format;
    } else {
      t.error = "cannot tell the mesh format of '" + output +
                "'; name it .obj, .ply, .off or .stl, or give " +
                defaults.format_flag;
    }
  }
  if (t.error.empty() && fs::is_directory(t.path, ec)) {
    t.error = CannotWrite(t.path, EISDIR);
  }
  // `-o DIR/` beside the input, or -o naming it: the write would replace
  // the input with its own result.
  if (t.error.empty() && SameFile(input, t.path)) {
    t.error = "-o '" + output + "' would overwrite the input '" + input +
              "': name another file or directory";
  }
  return t;
}

// An ostream buffer over a file descriptor that keeps the errno of a
// failed write.
class AtomicOutput::Buffer : public std::streambuf {
 public:
  explicit Buffer(int fd) : fd_(fd) { setp(data_, data_ + sizeof data_); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!Drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return Drain() ? 0 : -1; }

 private:
  bool Drain() {
    const char* p = pbase();
    while (p < pptr() && error_ == 0) {
      const ssize_t n = ::write(fd_, p, static_cast<size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        error_ = n < 0 ? errno : EIO;
        break;
      }
      p += n;
    }
    setp(data_, data_ + sizeof data_);
    return error_ == 0;
  }
  int fd_;
  int error_ = 0;
  char data_[1 << 16];
};

AtomicOutput::AtomicOutput() = default;

AtomicOutput::~AtomicOutput() {
  stream_.reset();
  buffer_.reset();
  if (fd_ > STDERR_FILENO) ::close(fd_);
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

std::string AtomicOutput::Open(const std::string& path) {
  path_ = path;
  if (path == "-") {
    std::cout.flush();
    fd_ = STDOUT_FILENO;
  } else {
    struct stat st;
    const bool exists = ::stat(path.c_str(), &st) == 0;
    if (!exists && errno != ENOENT) return CannotWrite(path, errno);
    if (exists && S_ISDIR(st.st_mode)) return CannotWrite(path, EISDIR);
    if (exists && !S_ISREG(st.st_mode)) {
      // A device or a pipe: written in place, nothing to rename.
      fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
      if (fd_ < 0) return CannotWrite(path, errno);
    } else {
      if (exists && ::access(path.c_str(), W_OK) != 0) {
        return CannotWrite(path, errno);
      }
      const fs::path p(path);
      const fs::path dir = p.has_parent_path() ? p.parent_path() : ".";
      std::string temp =
          (dir / ("." + p.filename().string() + ".XXXXXX")).string();
      fd_ = ::mkstemp(temp.data());
      if (fd_ < 0) return CannotWrite(path, errno);
      temp_ = temp;
      mode_t mode;
      if (exists) {
        mode = st.st_mode & 07777;
      } else {
        const mode_t mask = ::umask(0);
        ::umask(mask);
        mode = 0666 & ~mask;
      }
      (void)::fchmod(fd_, mode);
    }
  }
  buffer_ = std::make_unique<Buffer>(fd_);
  stream_ = std::make_unique<std::ostream>(buffer_.get());
  return "";
}

std::ostream& AtomicOutput::stream() { return *stream_; }

std::string AtomicOutput::Commit() {
  stream_->flush();
  if (buffer_->error() != 0) return CannotWrite(path_, buffer_->error());
  if (!*stream_) return CannotWrite(path_, EIO);
  if (fd_ > STDERR_FILENO) {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) return CannotWrite(path_, errno);
  }
  if (!temp_.empty()) {
    if (::rename(temp_.c_str(), path_.c_str()) != 0) {
      return CannotWrite(path_, errno);
    }
    temp_.clear();
  }
  return "";
}

std::string WriteOutput(const OutputTarget& target, const MeshData& mesh) {
  AtomicOutput out;
  std::string error = out.Open(target.Name());
  if (!error.empty()) return error;
  const Status s = WriteMesh(out.stream(), target.format, mesh);
  error = out.Commit();
  if (error.empty() && !s.ok()) error = s.message;
  return error;
}

}  // namespace dot::client
