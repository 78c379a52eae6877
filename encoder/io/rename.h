// The two renames an output needs beyond rename(2): one that never replaces what is at the
// target (two writers racing for a new name: the second fails, it never clobbers the first),
// and one that swaps two folders in one step (a folder of frames replaced as a whole).
#pragma once

namespace dcurve {

// Renames `from` to `to` only if `to` does not exist (errno EEXIST otherwise). Linux: one
// renameat2(RENAME_NOREPLACE); elsewhere, or on a file system without it, a file is linked
// then unlinked, and a folder is renamed after a check.
int rename_no_replace(const char* from, const char* to);

// Exchanges two paths atomically (renameat2 RENAME_EXCHANGE, macOS renamex_np RENAME_SWAP).
// -1 with errno ENOTSUP where the system or file system has no such call.
int rename_exchange(const char* a, const char* b);

}  // namespace dcurve
