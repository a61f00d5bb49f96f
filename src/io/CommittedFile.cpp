// The committing HDF5 file driver (CommittedFile.hpp): POSIX reads and writes on a work file, and
// commit() = atomic name exchange plus catching the new work file up.
#include "CommittedFile.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

namespace strand::io::h5 {

namespace {

struct Driver {
  H5FD_t pub;  // first member: HDF5 hands us back &pub
  std::string path, work;
  int fd = -1;  // the work file; HDF5 reads and writes only here
  haddr_t eoa = 0, eof = 0;
  std::vector<std::pair<haddr_t, haddr_t>> written;  // [begin, end) since the last commit
  bool published = false;                            // the result holds a commit of this file
  bool broken = false;  // a commit failed after publishing: no more writes (they would go in place)
};

constexpr haddr_t kMaxAddr = (static_cast<haddr_t>(1) << (8 * sizeof(off_t) - 1)) - 1;

std::string reason(const std::string& what) { return what + ": " + std::strerror(errno); }

herr_t failure(const char* function, const std::string& message) {
  H5Epush2(H5E_DEFAULT, __FILE__, function, __LINE__, H5E_ERR_CLS, H5E_VFL, H5E_WRITEERROR, "%s", message.c_str());
  return -1;
}

// Copies [begin, end) of `from` to the same place in `to`.
void copyRange(int from, int to, off_t begin, off_t end) {
  off_t in = begin, out = begin;
  while (in < end) {
    const ssize_t n = copy_file_range(from, &in, to, &out, static_cast<size_t>(end - in), 0);
    if (n > 0) continue;
    if (n == 0) break;  // end of the source
    if (errno != EXDEV && errno != ENOSYS && errno != EINVAL && errno != EOPNOTSUPP)
      throw std::runtime_error(reason("cannot copy into the work file"));
    std::vector<char> buf(1 << 20);  // no copy_file_range here: plain reads and writes
    while (in < end) {
      const ssize_t r = pread(from, buf.data(), std::min<off_t>(end - in, buf.size()), in);
      if (r <= 0) throw std::runtime_error(reason("cannot read the committed file"));
      for (ssize_t done = 0; done < r;) {
        const ssize_t w = pwrite(to, buf.data() + done, r - done, in + done);
        if (w < 0) throw std::runtime_error(reason("cannot write the work file"));
        done += w;
      }
      in += r;
    }
  }
}

H5FD_t* open(const char* name, unsigned flags, hid_t, haddr_t maxaddr) {
  // HDF5 first tries to open without TRUNC (to see whether the file is open already): refuse, so
  // that it creates
  if (!(flags & H5F_ACC_TRUNC)) {
    failure(__func__, "the committing driver only creates files");
    return nullptr;
  }
  if (maxaddr == 0 || maxaddr > kMaxAddr) maxaddr = kMaxAddr;
  auto* f = new Driver;
  f->path = name;
  f->work = workFilePath(name);
  f->fd = ::open(f->work.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (f->fd < 0) {
    failure(__func__, reason("cannot create '" + f->work + "'"));
    delete f;
    return nullptr;
  }
  // a work file left by a killed run is reused; one that a live run holds is not
  if (flock(f->fd, LOCK_EX | LOCK_NB) != 0 || ftruncate(f->fd, 0) != 0) {
    failure(__func__, "'" + f->work + "' is in use: another run is writing '" + f->path + "'");
    ::close(f->fd);
    delete f;
    return nullptr;
  }
  f->pub.maxaddr = maxaddr;
  return &f->pub;
}

herr_t close(H5FD_t* file) {
  auto* f = reinterpret_cast<Driver*>(file);
  herr_t status = 0;
  if (::close(f->fd) != 0) status = failure(__func__, reason("cannot close '" + f->work + "'"));
  ::unlink(f->work.c_str());  // the spare copy (or, without a commit, the only one)
  delete f;
  return status;
}

int compare(const H5FD_t* a, const H5FD_t* b) {
  const int c = reinterpret_cast<const Driver*>(a)->path.compare(reinterpret_cast<const Driver*>(b)->path);
  return c < 0 ? -1 : c > 0 ? 1 : 0;
}

herr_t query(const H5FD_t*, unsigned long* flags) {
  *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
           H5FD_FEAT_AGGREGATE_SMALLDATA | H5FD_FEAT_DEFAULT_VFD_COMPATIBLE;
  return 0;
}

haddr_t getEoa(const H5FD_t* file, H5FD_mem_t) { return reinterpret_cast<const Driver*>(file)->eoa; }
herr_t setEoa(H5FD_t* file, H5FD_mem_t, haddr_t addr) {
  reinterpret_cast<Driver*>(file)->eoa = addr;
  return 0;
}
haddr_t getEof(const H5FD_t* file, H5FD_mem_t) { return reinterpret_cast<const Driver*>(file)->eof; }

herr_t getHandle(H5FD_t* file, hid_t, void** handle) {
  *handle = file;
  return 0;
}

herr_t read(H5FD_t* file, H5FD_mem_t, hid_t, haddr_t addr, size_t size, void* buffer) {
  auto* f = reinterpret_cast<Driver*>(file);
  if (addr > kMaxAddr || size > kMaxAddr - addr) return failure(__func__, "read beyond the largest address");
  auto* p = static_cast<char*>(buffer);
  while (size > 0) {
    const ssize_t n = pread(f->fd, p, size, static_cast<off_t>(addr));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return failure(__func__, reason("cannot read '" + f->work + "'"));
    if (n == 0) {  // beyond the end of the file: zeros, as the sec2 driver does
      std::memset(p, 0, size);
      break;
    }
    p += n;
    addr += n;
    size -= n;
  }
  return 0;
}

herr_t write(H5FD_t* file, H5FD_mem_t, hid_t, haddr_t addr, size_t size, const void* buffer) {
  auto* f = reinterpret_cast<Driver*>(file);
  if (f->broken) return failure(__func__, "an earlier commit of '" + f->path + "' failed");
  if (addr > kMaxAddr || size > kMaxAddr - addr) return failure(__func__, "write beyond the largest address");
  if (!f->written.empty() && f->written.back().second == addr) f->written.back().second = addr + size;
  else f->written.emplace_back(addr, addr + size);
  const auto* p = static_cast<const char*>(buffer);
  for (size_t left = size; left > 0;) {
    const ssize_t n = pwrite(f->fd, p, left, static_cast<off_t>(addr));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return failure(__func__, reason("cannot write '" + f->work + "'"));
    p += n;
    addr += n;
    left -= n;
  }
  f->eof = std::max(f->eof, addr);
  return 0;
}

herr_t truncate(H5FD_t* file, hid_t, hbool_t) {
  auto* f = reinterpret_cast<Driver*>(file);
  if (f->eoa == f->eof) return 0;
  if (ftruncate(f->fd, static_cast<off_t>(f->eoa)) != 0) return failure(__func__, reason("cannot resize '" + f->work + "'"));
  f->eof = f->eoa;
  return 0;
}

H5FD_class_t makeClass() {
  H5FD_class_t c{};
  c.name = "strand_committed";
  c.maxaddr = kMaxAddr;
  c.fc_degree = H5F_CLOSE_WEAK;
  c.open = open;
  c.close = close;
  c.cmp = compare;
  c.query = query;
  c.get_eoa = getEoa;
  c.set_eoa = setEoa;
  c.get_eof = getEof;
  c.get_handle = getHandle;
  c.read = read;
  c.write = write;
  c.truncate = truncate;
  const H5FD_mem_t map[] = H5FD_FLMAP_DICHOTOMY;
  std::copy(std::begin(map), std::end(map), c.fl_map);
  return c;
}

hid_t driverId() {
  static const H5FD_class_t cls = makeClass();
  static hid_t id = H5I_INVALID_HID;
  if (id < 0 || H5Iis_valid(id) <= 0) id = H5FDregister(&cls);
  return id;
}

void publish(Driver& f) {
  // the flushed file must reach the end of the space its superblock declares
  if (f.eoa > f.eof) {
    if (ftruncate(f.fd, static_cast<off_t>(f.eoa)) != 0) throw std::runtime_error(reason("cannot resize the work file"));
    f.eof = f.eoa;
  }
  bool exchanged = false;
  if (renameat2(AT_FDCWD, f.work.c_str(), AT_FDCWD, f.path.c_str(), RENAME_EXCHANGE) == 0) {
    exchanged = true;
  } else if (errno == EINVAL || errno == ENOSYS || errno == EOPNOTSUPP) {
    // no exchange on this file system (NFS): the same with a hard link to the result, so that it can
    // become the next work file; without hard links, a plain rename (and a full copy below)
    const std::string held = f.work + ".previous";
    ::unlink(held.c_str());
    const bool linked = ::link(f.path.c_str(), held.c_str()) == 0;
    if (std::rename(f.work.c_str(), f.path.c_str()) != 0) {
      if (linked) ::unlink(held.c_str());
      throw std::runtime_error(reason("cannot rename the work file"));
    }
    exchanged = linked && std::rename(held.c_str(), f.work.c_str()) == 0;
  } else if (errno == ENOENT) {  // no result yet: a plain rename is atomic too
    if (std::rename(f.work.c_str(), f.path.c_str()) != 0) throw std::runtime_error(reason("cannot rename the work file"));
  } else {
    throw std::runtime_error(reason("cannot exchange the work file with the result"));
  }
  flock(f.fd, LOCK_UN);  // the result now: readers may lock it while the new work file is made
  // The new work file: the previous result when it held our previous commit and no reader has it
  // open, else a fresh copy.
  int spare = -1;
  bool upToDate = false;
  if (exchanged) {
    spare = ::open(f.work.c_str(), O_RDWR | O_CLOEXEC);
    if (spare >= 0 && flock(spare, LOCK_EX | LOCK_NB) != 0) {
      ::close(spare);
      ::unlink(f.work.c_str());
      spare = -1;
    } else {
      upToDate = spare >= 0 && f.published;
    }
  }
  f.broken = true;  // until the new work file is complete
  if (spare < 0) {
    spare = ::open(f.work.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (spare < 0 || flock(spare, LOCK_EX | LOCK_NB) != 0) throw std::runtime_error(reason("cannot create the work file"));
  }
  try {
    if (upToDate) {
      std::sort(f.written.begin(), f.written.end());
      haddr_t begin = 0, end = 0;
      for (const auto& [b, e] : f.written) {
        if (b > end) {
          if (end > begin) copyRange(f.fd, spare, static_cast<off_t>(begin), static_cast<off_t>(std::min(end, f.eof)));
          begin = b;
        }
        end = std::max(end, e);
      }
      if (end > begin) copyRange(f.fd, spare, static_cast<off_t>(begin), static_cast<off_t>(std::min(end, f.eof)));
    } else {
      copyRange(f.fd, spare, 0, static_cast<off_t>(f.eof));
    }
    if (ftruncate(spare, static_cast<off_t>(f.eof)) != 0) throw std::runtime_error(reason("cannot resize the work file"));
  } catch (...) {
    ::close(spare);
    throw;
  }
  ::close(f.fd);  // the published file
  f.fd = spare;
  f.written.clear();
  f.published = true;
  f.broken = false;
}

}  // namespace

std::string workFilePath(const std::string& path) {
  const std::filesystem::path p(path);
  return (p.parent_path() / ("." + p.filename().string() + ".strand-work")).string();
}

hid_t committedFileAccess() {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0) throw std::runtime_error("cannot create a file access property list");
  if (H5Pset_driver(fapl, driverId(), nullptr) < 0) {
    H5Pclose(fapl);
    throw std::runtime_error("cannot select the committing file driver");
  }
  return fapl;
}

void commit(hid_t file) {
  void* handle = nullptr;
  if (H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) < 0 || !handle)
    throw std::runtime_error("not a file of the committing driver");
  publish(*static_cast<Driver*>(handle));
}

}  // namespace strand::io::h5
