// HDF5 files that change on disk only by atomic commits: a file driver (HDF5 "virtual file
// driver") for outputs that a killed run must leave readable (issue 32 item 4). Internal to src/io.
//
// Why: HDF5 updates its metadata (group B-trees, local heaps, dataset headers) in place, with
// several writes per change, and writes evicted metadata at any moment, not only at H5Fflush. A
// run killed between two such writes leaves a file whose groups cannot be read ("bad heap free
// list", "bad symbol table node signature": 3 of 150 kill -9 tests of the flush-per-frame
// writer). No order of flushes avoids that for a file that is written in place.
//
// How: HDF5 writes into a hidden work file next to the result, `.<name>.strand-work`; the result
// itself is only ever replaced by rename(2), which is atomic. commit(), called after H5Fflush (the
// work file is then a complete, consistent HDF5 file), swaps the two names (renameat2
// RENAME_EXCHANGE): the result becomes the flushed file, and the previous result becomes the work
// file. That one is brought up to date by copying the byte ranges written since the previous commit
// (copy_file_range), and HDF5 goes on writing there. So the result is, at every instant, the file as
// it was at some commit, whatever kills the process when; the cost is one more copy of what each
// commit wrote, and a work file as large as the result while the run lasts (removed at close; a
// killed run leaves it, and the next run to the same result reuses it). A reader that has the
// result open keeps a consistent view: if it holds HDF5's lock on it, the next commit makes a fresh
// work file instead of reusing that one. Commits may be per frame or per block of frames: whatever
// H5Fflush made consistent is what the next commit publishes.
//
// The files are plain HDF5 files (no driver information in the superblock): any reader (h5py,
// ParaView) opens the result with the default driver. Only file creation is supported.
#pragma once
#include <hdf5.h>

#include <string>

namespace strand::io::h5 {

// A file access property list for H5Fcreate whose file is written through the committing driver.
// Caller closes it.
hid_t committedFileAccess();

// After H5Fflush(file): publishes the flushed state as the result, atomically. Throws
// std::runtime_error (with errno's text) if a file-system call fails; the result then keeps its
// previous commit.
void commit(hid_t file);

// The work file of the result `path` (for messages and clean-up).
std::string workFilePath(const std::string& path);

}  // namespace strand::io::h5
