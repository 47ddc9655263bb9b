// SPDX-License-Identifier: AGPL-3.0-or-later
#include "cli/inputs.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

namespace dot::client {

namespace fs = std::filesystem;

std::vector<std::string> ExpandInputs(
    const std::vector<std::string>& args, std::string* error,
    const std::vector<std::string>& extensions) {
  std::vector<std::string> files;
  const auto add = [&](const std::string& file) { files.push_back(file); };
  for (const std::string& a : args) {
    std::error_code ec;
    if (a != "-" && fs::is_directory(a, ec)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(a, ec)) {
        std::string ext = e.path().extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(),
                       [](unsigned char c) { return std::tolower(c); });
        if (e.is_regular_file() &&
            std::find(extensions.begin(), extensions.end(), ext) !=
                extensions.end()) {
          found.push_back(e.path().string());
        }
      }
      std::sort(found.begin(), found.end());
      for (const std::string& f : found) add(f);
    } else {
      add(a);  // "-", a file, or a name the reader will refuse
    }
  }
  if (files.empty() && error->empty()) {
    *error = "no files found (looked for";
    for (const std::string& ext : extensions) *error += " *" + ext;
    *error += ")";
  }
  return files;
}

std::vector<std::string> EachOnce(const std::vector<std::string>& files,
                                  std::vector<std::string>* dropped) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (const std::string& file : files) {
    // A path as written, made absolute with `.` and `..` resolved: links
    // are not followed (a link is its own input, written under its own
    // name); a stream is its name.
    std::error_code ec;
    const fs::path absolute = fs::absolute(file, ec);
    const std::string key =
        IsStreamInput(file) || ec ? file : absolute.lexically_normal().string();
    if (seen.insert(key).second) {
      out.push_back(file);
    } else if (dropped != nullptr) {
      dropped->push_back(file);
    }
  }
  return out;
}

bool IsStreamInput(const std::string& input) {
  // /dev/stdin and /proc/self/fd/0 resolve to a regular file when stdin is
  // redirected from one: known by name.
  if (input == "-" || input == "/dev/stdin" ||
      input.rfind("/dev/fd/", 0) == 0 ||
      (input.rfind("/proc/", 0) == 0 &&
       input.find("/fd/") != std::string::npos)) {
    return true;
  }
  struct stat st;
  return ::stat(input.c_str(), &st) == 0 && !S_ISREG(st.st_mode) &&
         !S_ISDIR(st.st_mode);
}

Status ReadPolygonInput(const std::string& input, const std::string& format,
                        PolygonData* out, std::vector<std::string>* notes) {
  if (input != "-" && (format.empty() || !IsStreamInput(input))) {
    return ReadPolygonFile(input, out, notes);
  }
  const bool obj = format == "obj";
  Status s;
  if (input == "-") {
    s = obj ? ReadPolygonObj(std::cin, out, notes)
            : ReadPolygonText(std::cin, out, notes);
    if (!s.ok()) s.message = "stdin: " + s.message;
    return s;
  }
  errno = 0;
  std::ifstream in(input);
  if (!in) {
    return InvalidArgument(
        "cannot open polygon file '" + input + "'" +
        (errno ? std::string(": ") + std::strerror(errno) : std::string()));
  }
  s = obj ? ReadPolygonObj(in, out, notes) : ReadPolygonText(in, out, notes);
  if (!s.ok()) s.message = input + ": " + s.message;
  return s;
}

Status ReadMeshInput(const std::string& input, const std::string& format,
                     PolygonSoup* soup, std::vector<std::string>* notes) {
  if (!IsStreamInput(input)) {
    return ReadPolygonSoupFile(input, soup, notes);
  }
  if (format.empty()) {
    return InvalidArgument("reading a mesh from stdin needs --input-format");
  }
  char name[] = "/tmp/dotctl-stdin-XXXXXX";
  const int fd = mkstemp(name);
  if (fd < 0) return InvalidArgument("cannot make a temporary file");
  close(fd);
  const std::string path = std::string(name) + "." + format;
  std::rename(name, path.c_str());
  {
    std::ofstream tmp(path, std::ios::binary);
    if (input == "-") {
      tmp << std::cin.rdbuf();
    } else {
      std::ifstream in(input, std::ios::binary);
      tmp << in.rdbuf();
    }
  }
  Status s = ReadPolygonSoupFile(path, soup, notes);
  std::remove(path.c_str());
  // Errors name what the user gave, not the temporary copy.
  const std::string shown = input == "-" ? "stdin" : "'" + input + "'";
  for (size_t at;
       (at = s.message.find("'" + path + "'")) != std::string::npos;) {
    s.message.replace(at, path.size() + 2, shown);
  }
  for (size_t at; (at = s.message.find(path)) != std::string::npos;) {
    s.message.replace(at, path.size(), shown);
  }
  return s;
}

}  // namespace dot::client
