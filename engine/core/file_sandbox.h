// The sandbox of files a scene may read (issue 16): the references in a scene
// file (buffer and image URIs) are resolved against the scene's own folder and
// refused when they land outside it and outside every folder the user allowed.
// Symlinks are followed before the containment check, so a link inside the
// folder that points out is refused like the path it points to.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace quadra {

// The canonical form of a folder the user allows (--allow-path); an Error
// naming it when it is not an existing folder.
std::filesystem::path canonicalAllowedFolder(const std::string& folder);

class FileSandbox {
 public:
  // home: the folder relative references start from (the scene file's);
  // allowed: further folders, each checked by canonicalAllowedFolder.
  FileSandbox(const std::filesystem::path& home, const std::vector<std::string>& allowed);

  struct Resolved {
    std::filesystem::path path;  // canonical; meaningful when refusal is empty
    std::string refusal;         // why it may not be read, to follow the reference
  };

  // A percent-decoded reference: a relative path (may land in home or an
  // allowed folder), an absolute path or a file: URI (only in an allowed
  // folder: the scene's own folder is reached by relative references, so a
  // file that names absolute paths reads nothing the user did not name).
  // Other URI schemes are refused; so is anything that exists but is not a
  // regular file (a FIFO would block the load, a device never end).
  Resolved resolve(const std::string& reference) const;

  const std::filesystem::path& home() const { return home_; }

 private:
  bool inAllowedFolder(const std::filesystem::path& canonical) const;

  std::filesystem::path home_;
  std::vector<std::filesystem::path> allowed_;
};

}  // namespace quadra
