// Files written whole or not at all: every writer of tripath's outputs (images, glTF, reports,
// checkpoints) writes a temporary file beside the target and renames it over the target, so an
// interrupted or failed write never leaves a truncated file under the real name; the temporaries
// a killed writer left are removed by the next write of the same target.
#pragma once
#include <functional>
#include <ostream>
#include <string>

namespace tripath {

// Throws InputError ("cannot write '<path>': …") if `path` cannot be a file: empty, in a folder
// that does not exist or is not a folder, itself a folder, or an existing symbolic link, device,
// FIFO or socket. Cheap: meant to be called before long work, so a typo costs nothing.
void checkTarget(const std::string& path);

// checkTarget, and a file can really be created in the folder (permissions, ACLs, read-only mounts):
// throws InputError naming the folder otherwise. Meant to be called before a long render.
void checkWritable(const std::string& path);

// Replaces `path` by what `write(tmp)` writes to `tmp`, a new file in the same folder (one
// filesystem, so the rename is atomic) whose name ends in `ext`, so that a tool finding a leftover
// still recognises it. On any failure the temporary is removed and the exception goes on; a failed
// rename throws InputError. Once `path` is replaced, the temporaries of `path` whose writing process
// is gone (named with its pid: "<path>.tmp-<pid>-<n><ext>") are removed too. No fsync: this protects against failed and concurrent writes, not
// against power loss, which is not worth the cost for a renderer's output.
void replaceAtomically(const std::string& path, const std::string& ext, const std::function<void(const std::string&)>& write);

// The same for a stream that `write` fills; a file that cannot be opened or a write that fails
// (disk full) throws InputError naming `path`.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace tripath
