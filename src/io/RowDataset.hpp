// A dataset that grows by rows: dimension 0 unlimited, each row of a fixed shape (none: a 1-D
// dataset of scalars). Rows are buffered in memory and appended by one extent change and one
// write per commit (OutputWriter's blocks). Internal to src/io; rank 0 only.
#pragma once
#include <hdf5.h>

#include <algorithm>
#include <string>
#include <vector>

#include "Hdf5.hpp"

namespace strand::io {

class RowDataset {
public:
  // `rowShape`: the shape of one row; chunks of about `chunkBytes` (at least one row).
  void create(hid_t loc, const std::string& path, std::vector<hsize_t> rowShape, std::size_t chunkBytes) {
    using namespace h5;
    path_ = path;
    shape_ = std::move(rowShape);
    rowSize_ = 1;
    for (hsize_t d : shape_) rowSize_ *= d;
    std::vector<hsize_t> dims{0}, maxDims{H5S_UNLIMITED}, chunk{std::max<hsize_t>(1, chunkBytes / (8 * rowSize_))};
    dims.insert(dims.end(), shape_.begin(), shape_.end());
    maxDims.insert(maxDims.end(), shape_.begin(), shape_.end());
    chunk.insert(chunk.end(), shape_.begin(), shape_.end());
    Hid space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxDims.data()), "cannot create dataspace"),
              H5Sclose);
    Hid dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "cannot create property list"), H5Pclose);
    check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), "cannot set chunking");
    check(H5Pset_obj_track_times(dcpl.get(), false), "cannot set dataset properties");
    dset_ = Hid(check(H5Dcreate2(loc, path.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                      "cannot create dataset '" + path + "'"),
                H5Dclose);
  }
  bool created() const { return static_cast<bool>(dset_); }

  void buffer(const double* values, std::size_t n) { pending_.insert(pending_.end(), values, values + n); }
  std::size_t pendingValues() const { return pending_.size(); }
  const std::vector<double>& pending() const { return pending_; }  // row-major, not yet in the file
  hsize_t rows() const { return rows_; }  // rows in the file

  // Appends the buffered rows to the file (they count as rows() after committed()).
  void write() {
    using namespace h5;
    if (pending_.empty()) return;
    const hsize_t add = pending_.size() / rowSize_;
    std::vector<hsize_t> size{rows_ + add}, start{rows_}, count{add};
    size.insert(size.end(), shape_.begin(), shape_.end());
    count.insert(count.end(), shape_.begin(), shape_.end());
    start.resize(count.size(), 0);
    check(H5Dset_extent(dset_.get(), size.data()), "cannot extend dataset '" + path_ + "'");
    Hid fspace(check(H5Dget_space(dset_.get()), "cannot get dataspace of '" + path_ + "'"), H5Sclose);
    check(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
          "cannot select in '" + path_ + "'");
    Hid mspace(check(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), "cannot create dataspace"),
               H5Sclose);
    check(H5Dwrite(dset_.get(), H5T_NATIVE_DOUBLE, mspace.get(), fspace.get(), H5P_DEFAULT, pending_.data()),
          "cannot write dataset '" + path_ + "'");
  }
  // After a commit: the buffered rows are in the file.
  void committed() {
    rows_ += pending_.size() / rowSize_;
    pending_.clear();
  }
  // After a failed commit: back to the committed rows (best effort), the buffer dropped.
  void rollback() {
    if (dset_) {
      std::vector<hsize_t> size{rows_};
      size.insert(size.end(), shape_.begin(), shape_.end());
      H5Dset_extent(dset_.get(), size.data());
    }
    pending_.clear();
  }
  void close() { dset_.close("cannot close dataset '" + path_ + "'"); }

private:
  h5::Hid dset_;
  std::string path_;
  std::vector<hsize_t> shape_;
  hsize_t rowSize_ = 1, rows_ = 0;
  std::vector<double> pending_;
};

}  // namespace strand::io
