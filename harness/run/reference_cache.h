#pragma once
// On-disk cache of exact reference images, so re-runs and later sweeps do not
// pay for the reference again. The key covers the scene's content hash (its
// geometry, colours and camera), the size, the background, the source
// revision and the reference technique's shaders, so a changed scene or
// reference never reads a stale image.
#include <optional>
#include <string>

#include "harness/output/image.h"

namespace oit {

class ReferenceCache {
 public:
  // `directory` empty: caching is off.
  explicit ReferenceCache(std::string directory);
  // $OIT_REFERENCE_CACHE ("off" disables), else $XDG_CACHE_HOME/oitbench/references,
  // else ~/.cache/oitbench/references.
  static ReferenceCache from_environment();

  bool enabled() const { return !directory_.empty(); }
  const std::string& directory() const { return directory_; }
  std::string path_for(const std::string& key) const;
  // A miss, never an error, for anything but a whole entry of `key` (of
  // `width` x `height` where those are given, > 0): a missing file quietly;
  // with a warning on stderr naming the file and the problem a FIFO, device,
  // directory or unreadable file in its place (refused by what it is,
  // without reading it), and a file whose header is foreign, whose declared
  // image does not fit its length (checked before anything is allocated),
  // whose image is of another size, whose checksum does not match or whose
  // image holds non-finite values. A regular file is then replaced by the
  // next store(); anything else in the way is left, and store() says so.
  std::optional<Image> load(const std::string& key, int width = 0, int height = 0) const;
  // Written through write_file_atomically with a checksum at the end, so a
  // crash leaves no half file and damage is found. A failure to write only
  // costs the cache: it is reported on stderr, the run goes on.
  void store(const std::string& key, const Image& image) const;

 private:
  std::string directory_;
};

}  // namespace oit
