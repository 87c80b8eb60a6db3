// Resolution and containment of a scene's file references (file_sandbox.h).
#include "core/file_sandbox.h"

#include <algorithm>
#include <cctype>
#include <system_error>

#include "core/error.h"

namespace quadra {

namespace fs = std::filesystem;

namespace {

// Whether `path` is `folder` or below it; both canonical, so a component-wise
// prefix is containment ("/a/bc" is not below "/a/b").
bool isWithin(const fs::path& path, const fs::path& folder) {
  return std::mismatch(folder.begin(), folder.end(), path.begin(), path.end()).first ==
         folder.end();
}

// The scheme of an absolute URI (RFC 3986 §3.1: a letter, then letters,
// digits, '+', '-' or '.', then ':'), lower-cased; empty for a path.
std::string uriScheme(const std::string& reference) {
  const std::size_t colon = reference.find(':');
  if (colon == std::string::npos || colon == 0) return "";
  if (!std::isalpha(static_cast<unsigned char>(reference[0]))) return "";
  std::string scheme;
  for (std::size_t i = 0; i < colon; ++i) {
    const auto c = static_cast<unsigned char>(reference[i]);
    if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') return "";
    scheme += char(std::tolower(c));
  }
  return scheme;
}

}  // namespace

fs::path canonicalAllowedFolder(const std::string& folder) {
  std::error_code ec;
  const fs::path canonical = fs::canonical(folder, ec);
  if (ec || !fs::is_directory(canonical, ec)) {
    throw Error("--allow-path: '" + folder + "' is not an existing folder");
  }
  return canonical;
}

FileSandbox::FileSandbox(const fs::path& home, const std::vector<std::string>& allowed) {
  std::error_code ec;
  const fs::path folder = fs::absolute(home.empty() ? fs::path(".") : home, ec);
  if (!ec) home_ = fs::weakly_canonical(folder, ec);
  if (ec) throw Error(home.string() + ": cannot resolve the folder (" + ec.message() + ")");
  for (const std::string& dir : allowed) allowed_.push_back(canonicalAllowedFolder(dir));
}

bool FileSandbox::inAllowedFolder(const fs::path& canonical) const {
  return std::any_of(allowed_.begin(), allowed_.end(),
                     [&](const fs::path& folder) { return isWithin(canonical, folder); });
}

FileSandbox::Resolved FileSandbox::resolve(const std::string& reference) const {
  if (reference.find('\0') != std::string::npos) return {{}, "contains a NUL byte"};
  // 1. The path the reference names: file: URIs (RFC 8089) name absolute
  //    paths on this machine; no other scheme is a file.
  std::string path = reference;
  const std::string scheme = uriScheme(reference);
  const bool fileUri = scheme == "file";
  if (fileUri) {
    path = reference.substr(5);
    if (path.rfind("//", 0) == 0) {
      const std::size_t slash = path.find('/', 2);
      const std::string host = path.substr(2, slash == std::string::npos ? slash : slash - 2);
      if (!host.empty() && host != "localhost") {
        return {{}, "names the host '" + host + "' (file: URIs are read from this machine only)"};
      }
      path = slash == std::string::npos ? "" : path.substr(slash);
    }
    if (path.empty() || path[0] != '/') return {{}, "is a file: URI without an absolute path"};
  } else if (!scheme.empty()) {
    return {{},
            "has the scheme '" + scheme +
                ":', which is not read (only relative paths, file: in an --allow-path "
                "folder, and data:)"};
  }
  // 2. Resolved against home, symlinks followed.
  const bool absolute = fs::path(path).is_absolute();
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(home_ / path, ec);
  if (ec) return {{}, "cannot be resolved (" + ec.message() + ")"};
  // 3. Contained: relative references in home or an allowed folder, absolute
  //    ones in an allowed folder only.
  if (absolute && !inAllowedFolder(canonical)) {
    return {{},
            std::string(fileUri ? "is a file: URI" : "is an absolute path") +
                (canonical.string() == path ? "" : " (resolving to " + canonical.string() + ")") +
                " outside every --allow-path folder"};
  }
  if (!absolute && !isWithin(canonical, home_) && !inAllowedFolder(canonical)) {
    return {{},
            "resolves to " + canonical.string() + ", outside the scene's folder " + home_.string() +
                " (--allow-path widens it)"};
  }
  if (fs::exists(canonical, ec) && !fs::is_regular_file(canonical, ec)) {
    return {{}, "is not a regular file"};
  }
  return {canonical, ""};
}

}  // namespace quadra
