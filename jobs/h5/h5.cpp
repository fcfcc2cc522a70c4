#include "jobs/h5/h5.h"

#include <H5DSpublic.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <exception>
#include <utility>

namespace skewbridge::jobs::h5 {

static_assert(sizeof(hid_t) == sizeof(std::int64_t), "hid_t is 64-bit since HDF5 1.10");

namespace {

// Collects the descriptions of the current error stack, most specific first.
herr_t CollectError(unsigned /*n*/, const H5E_error2_t* err, void* client) {
  if (err != nullptr && err->desc != nullptr) {
    static_cast<std::vector<std::string>*>(client)->emplace_back(err->desc);
  }
  return 0;
}

}  // namespace

std::string ErrorReason() {
  std::vector<std::string> descs;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, CollectError, &descs);
  H5Eclear2(H5E_DEFAULT);
  // The file drivers put the system's reason into the most specific entry as
  // "..., errno = 28, error message = 'No space left on device', ...": keep only that text.
  for (const std::string& d : descs) {
    const std::size_t at = d.find("error message = '");
    if (at != std::string::npos) {
      const std::size_t begin = at + 17;
      const std::size_t end = d.find('\'', begin);
      return d.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    }
  }
  for (const std::string& d : descs) {
    if (d.find("Fletcher32") != std::string::npos) {
      return "Fletcher-32 checksum mismatch";
    }
  }
  return descs.empty() ? std::string("HDF5 call failed") : descs.front();
}

herr_t Check(herr_t status, std::string_view what) {
  if (status < 0) {
    throw H5Error(std::string(what) + ": " + ErrorReason());
  }
  return status;
}

hid_t CheckId(hid_t id, std::string_view what) {
  if (id < 0) {
    throw H5Error(std::string(what) + ": " + ErrorReason());
  }
  return id;
}

Id& Id::operator=(Id&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0 && closer_ != nullptr) {
      closer_(id_);
    }
    id_ = other.id_;
    closer_ = other.closer_;
    other.id_ = -1;
  }
  return *this;
}

Id::~Id() {
  if (id_ >= 0 && closer_ != nullptr) {
    closer_(id_);  // a close failure cannot be reported from a destructor
  }
}

void SilenceErrorStack() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

// Without file locks: the single writer of a cube holds no lock, so that readers (inspect,
// h5py, a progress check) can open FILE.partial while the sweep runs; the checkpoint file is
// safe to read at any moment because after creation only raw bytes change.
// The 1.8 object format puts a checksum on the superblock, every object header and the
// attribute heaps, so a damaged byte of metadata is found on open as well.
Id UnlockedAccess() {
  Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate(file access)");
  Check(H5Pset_file_locking(fapl.get(), false, true), "H5Pset_file_locking");
  Check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST),
        "H5Pset_libver_bounds");
  return fapl;
}

namespace {

// Chunks hold whole rows along the last axis and grow over the preceding axes up to about
// this many elements (a spectrum is one contiguous read).
constexpr hsize_t kChunkTargetElements = 8192;

}  // namespace

std::vector<hsize_t> DefaultChunk(std::span<const hsize_t> shape) {
  std::vector<hsize_t> chunk(shape.size(), 1);
  hsize_t elements = 1;
  for (std::size_t k = shape.size(); k-- > 0;) {
    const hsize_t room = std::max<hsize_t>(1, kChunkTargetElements / elements);
    chunk[k] = k + 1 == shape.size() ? shape[k] : std::min(shape[k], room);
    elements *= chunk[k];
  }
  return chunk;
}

Id CreateFile(const std::string& path) {
  SilenceErrorStack();
  return Id(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, UnlockedAccess().get()), H5Fclose,
            "create file " + path);
}

Id OpenFile(const std::string& path, bool writable) {
  SilenceErrorStack();
  return Id(H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, UnlockedAccess().get()),
            H5Fclose, "open file " + path);
}

Id CreateGroup(hid_t parent, const std::string& name) {
  Id lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "H5Pcreate(link)");
  Check(H5Pset_create_intermediate_group(lcpl.get(), 1), "H5Pset_create_intermediate_group");
  return Id(H5Gcreate2(parent, name.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
            "create group " + name);
}

Id OpenGroup(hid_t parent, const std::string& name) {
  return Id(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), H5Gclose, "open group " + name);
}

bool Exists(hid_t parent, const std::string& name) {
  return Check(H5Lexists(parent, name.c_str(), H5P_DEFAULT), "H5Lexists " + name) > 0;
}

std::vector<std::string> ListChildren(hid_t group) {
  H5G_info_t info;
  Check(H5Gget_info(group, &info), "H5Gget_info");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t n =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    Check(static_cast<herr_t>(n < 0 ? -1 : 0), "H5Lget_name_by_idx");
    std::string name(static_cast<std::size_t>(n), '\0');
    Check(static_cast<herr_t>(H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i,
                                                 name.data(), name.size() + 1, H5P_DEFAULT) < 0
                                  ? -1
                                  : 0),
          "H5Lget_name_by_idx");
    names.push_back(name);
  }
  return names;
}

Id Dataspace(std::span<const hsize_t> shape) {
  return Id(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr), H5Sclose,
            "H5Screate_simple");
}

Id StringType() {
  Id type(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy(string)");
  Check(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size(variable)");
  Check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset(utf8)");
  return type;
}

Id CreateDataset(hid_t parent, const std::string& name, hid_t type, std::span<const hsize_t> shape,
                 std::span<const hsize_t> chunk, int deflate_level, const void* fill) {
  Id space = Dataspace(shape);
  Id dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate(dataset) " + name);
  const bool empty = shape.empty() || std::find(shape.begin(), shape.end(), 0) != shape.end();
  // HDF5 filters no variable-length data (the strings live in the global heap).
  const bool variable = Check(H5Tis_variable_str(type), "H5Tis_variable_str " + name) > 0;
  if (empty || variable) {
    // Nothing to checksum, or nothing HDF5 can checksum; it cannot chunk an extent of zero.
    Check(H5Pset_layout(dcpl.get(), H5D_CONTIGUOUS), "H5Pset_layout " + name);
  } else {
    const std::vector<hsize_t> chunks =
        chunk.empty() ? DefaultChunk(shape) : std::vector<hsize_t>(chunk.begin(), chunk.end());
    Check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunks.size()), chunks.data()),
          "H5Pset_chunk " + name);
    if (deflate_level > 0) {
      Check(H5Pset_shuffle(dcpl.get()), "H5Pset_shuffle " + name);
      Check(H5Pset_deflate(dcpl.get(), static_cast<unsigned>(deflate_level)),
            "H5Pset_deflate " + name);
    } else {
      // Every chunk is placed (with its fill) at creation; later writes rewrite chunks of the
      // same size in place, so the file neither grows nor moves metadata while a sweep runs.
      Check(H5Pset_alloc_time(dcpl.get(), H5D_ALLOC_TIME_EARLY), "H5Pset_alloc_time " + name);
    }
    // Last in the pipeline: the checksum covers the bytes as stored, and H5Dread fails on a
    // chunk whose bytes changed.
    Check(H5Pset_fletcher32(dcpl.get()), "H5Pset_fletcher32 " + name);
  }
  if (fill != nullptr) {
    Check(H5Pset_fill_value(dcpl.get(), type, fill), "H5Pset_fill_value " + name);
    Check(H5Pset_fill_time(dcpl.get(), H5D_FILL_TIME_ALLOC), "H5Pset_fill_time " + name);
  }
  return Id(
      H5Dcreate2(parent, name.c_str(), type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
      H5Dclose, "create dataset " + name);
}

Id OpenDataset(hid_t parent, const std::string& name) {
  return Id(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset " + name);
}

std::vector<hsize_t> Shape(hid_t dataset) {
  Id space(H5Dget_space(dataset), H5Sclose, "H5Dget_space");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  Check(rank, "H5Sget_simple_extent_ndims");
  std::vector<hsize_t> shape(static_cast<std::size_t>(rank));
  Check(H5Sget_simple_extent_dims(space.get(), shape.data(), nullptr), "H5Sget_simple_extent");
  return shape;
}

std::string ObjectName(hid_t obj) {
  const ssize_t n = H5Iget_name(obj, nullptr, 0);
  if (n <= 0) {
    return "";
  }
  std::string name(static_cast<std::size_t>(n), '\0');
  H5Iget_name(obj, name.data(), name.size() + 1);
  return name;
}

void WriteAll(hid_t dataset, hid_t mem_type, const void* data) {
  // A write that converts (strings, integers stored narrower) fills a type conversion buffer
  // that HDF5 allocates zeroed at its default size, 1 MiB, whatever the data: 256 fresh pages
  // and their faults for a table of a few values. One that holds the whole write (elements
  // times the larger of the two types' sizes, at least the 16 bytes of a variable-length
  // string in the file) converts the same elements in the same single pass.
  constexpr std::size_t kDefaultBuffer = std::size_t{1} << 20;  // H5D_TEMP_BUF_SIZE
  Id space(H5Dget_space(dataset), H5Sclose, "H5Dget_space");
  Id file_type(H5Dget_type(dataset), H5Tclose, "H5Dget_type");
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  const std::size_t element =
      std::max({H5Tget_size(mem_type), H5Tget_size(file_type.get()), std::size_t{16}});
  Id transfer;
  if (n >= 0 && static_cast<std::size_t>(n) < kDefaultBuffer / element) {
    transfer = Id(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate(transfer)");
    Check(H5Pset_buffer(transfer.get(), std::max<std::size_t>(1, n) * element, nullptr, nullptr),
          "H5Pset_buffer");
  }
  Check(H5Dwrite(dataset, mem_type, H5S_ALL, H5S_ALL,
                 transfer.get() >= 0 ? transfer.get() : H5P_DEFAULT, data),
        "H5Dwrite " + ObjectName(dataset));
}

void ReadAll(hid_t dataset, hid_t mem_type, void* data) {
  Check(H5Dread(dataset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
        "H5Dread " + ObjectName(dataset));
}

namespace {

// A box of a row-major array: start and count per axis.
struct Box {
  std::vector<hsize_t> start;
  std::vector<hsize_t> count;
};

// The boxes that tile the linear range [a, b) of a row-major array of `shape` (at most
// 2 rank - 1 of them): a partial head slab, whole slabs, a partial tail slab, recursively.
void RangeBoxes(std::uint64_t a, std::uint64_t b, std::span<const hsize_t> shape,
                std::vector<hsize_t>& prefix, std::vector<Box>& out) {
  if (a >= b) {
    return;
  }
  if (shape.size() == 1) {
    Box box{prefix, std::vector<hsize_t>(prefix.size(), 1)};
    box.start.push_back(a);
    box.count.push_back(b - a);
    out.push_back(std::move(box));
    return;
  }
  std::uint64_t inner = 1;
  for (std::size_t k = 1; k < shape.size(); ++k) {
    inner *= shape[k];
  }
  const auto recurse = [&](std::uint64_t slab, std::uint64_t from, std::uint64_t to) {
    prefix.push_back(slab);
    RangeBoxes(from, to, shape.subspan(1), prefix, out);
    prefix.pop_back();
  };
  std::uint64_t first = a / inner;
  const std::uint64_t last = b / inner;  // the slab holding b (exclusive end)
  if (first == last) {
    recurse(first, a - first * inner, b - first * inner);
    return;
  }
  if (a % inner != 0) {
    recurse(first, a % inner, inner);
    ++first;
  }
  if (last > first) {
    Box box{prefix, std::vector<hsize_t>(prefix.size(), 1)};
    box.start.push_back(first);
    box.count.push_back(last - first);
    for (std::size_t k = 1; k < shape.size(); ++k) {
      box.start.push_back(0);
      box.count.push_back(shape[k]);
    }
    out.push_back(std::move(box));
  }
  if (b % inner != 0) {
    recurse(last, 0, b % inner);
  }
}

// Cells in runs at least this long go as boxes; shorter runs go in one point selection.
constexpr std::size_t kShortestBoxRun = 8;

}  // namespace

Id OpenFileParallel(const std::string& path) {
  SilenceErrorStack();
  Id fapl = UnlockedAccess();
  Check(H5Pset_fapl_mpio(fapl.get(), MPI_COMM_WORLD, MPI_INFO_NULL), "H5Pset_fapl_mpio " + path);
  return Id(H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get()), H5Fclose,
            "open file (MPI-IO) " + path);
}

Id CellsSelection(std::span<const hsize_t> shape, std::span<const std::uint64_t> cells) {
  Id space = Dataspace(shape);
  Check(H5Sselect_none(space.get()), "H5Sselect_none");
  std::vector<Box> boxes;
  std::vector<hsize_t> prefix;
  for (std::size_t i = 0; i < cells.size();) {
    std::size_t j = i + 1;
    while (j < cells.size() && cells[j] == cells[j - 1] + 1) {
      ++j;
    }
    RangeBoxes(cells[i], cells[j - 1] + 1, shape, prefix, boxes);
    i = j;
  }
  for (const Box& box : boxes) {
    Check(H5Sselect_hyperslab(space.get(), H5S_SELECT_OR, box.start.data(), nullptr,
                              box.count.data(), nullptr),
          "H5Sselect_hyperslab");
  }
  return space;
}

void WriteSelectedCollective(hid_t dataset, hid_t mem_type, hid_t file_space, std::uint64_t count,
                             const void* packed) {
  const hsize_t n = count;
  Id memory = Dataspace(std::span<const hsize_t>(&n, 1));
  if (count == 0) {
    Check(H5Sselect_none(memory.get()), "H5Sselect_none");
  }
  Id dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "H5Pcreate(transfer)");
  Check(H5Pset_dxpl_mpio(dxpl.get(), H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio");
  Check(H5Dwrite(dataset, mem_type, memory.get(), file_space, dxpl.get(), packed),
        "H5Dwrite (collective) " + ObjectName(dataset));
}

void WriteCells(hid_t dataset, hid_t mem_type, std::size_t elem_size, const void* full,
                std::span<const std::uint64_t> cells) {
  if (cells.empty()) {
    return;
  }
  const std::vector<hsize_t> shape = Shape(dataset);
  const std::size_t rank = shape.size();
  // Runs of consecutive cells (a checkpoint's cells are mostly whole chunks) are written
  // straight from the full array, the same boxes selected in memory and in the file: a few
  // H5Dwrite calls per run instead of a coordinate per cell.
  std::vector<std::uint64_t> loose;
  std::vector<Box> boxes;
  std::vector<hsize_t> prefix;
  for (std::size_t i = 0; i < cells.size();) {
    std::size_t j = i + 1;
    while (j < cells.size() && cells[j] == cells[j - 1] + 1) {
      ++j;
    }
    if (rank == 0 || j - i < kShortestBoxRun) {
      loose.insert(loose.end(), cells.begin() + static_cast<std::ptrdiff_t>(i),
                   cells.begin() + static_cast<std::ptrdiff_t>(j));
    } else {
      boxes.clear();
      RangeBoxes(cells[i], cells[j - 1] + 1, shape, prefix, boxes);
      Id file_space(H5Dget_space(dataset), H5Sclose, "H5Dget_space");
      Id mem_space = Dataspace(shape);
      for (std::size_t k = 0; k < boxes.size(); ++k) {
        const H5S_seloper_t op = k == 0 ? H5S_SELECT_SET : H5S_SELECT_OR;
        Check(H5Sselect_hyperslab(file_space.get(), op, boxes[k].start.data(), nullptr,
                                  boxes[k].count.data(), nullptr),
              "H5Sselect_hyperslab");
        Check(H5Sselect_hyperslab(mem_space.get(), op, boxes[k].start.data(), nullptr,
                                  boxes[k].count.data(), nullptr),
              "H5Sselect_hyperslab");
      }
      Check(H5Dwrite(dataset, mem_type, mem_space.get(), file_space.get(), H5P_DEFAULT, full),
            "H5Dwrite(cells)");
    }
    i = j;
  }
  if (loose.empty()) {
    return;
  }
  std::vector<hsize_t> coords(loose.size() * rank);
  std::vector<unsigned char> gathered(loose.size() * elem_size);
  const auto* bytes = static_cast<const unsigned char*>(full);
  for (std::size_t i = 0; i < loose.size(); ++i) {
    std::uint64_t rest = loose[i];
    for (std::size_t k = rank; k-- > 0;) {
      coords[i * rank + k] = rest % shape[k];
      rest /= shape[k];
    }
    std::memcpy(&gathered[i * elem_size], bytes + loose[i] * elem_size, elem_size);
  }
  Id file_space(H5Dget_space(dataset), H5Sclose, "H5Dget_space");
  Check(H5Sselect_elements(file_space.get(), H5S_SELECT_SET, loose.size(), coords.data()),
        "H5Sselect_elements");
  const hsize_t n = loose.size();
  Id mem_space = Dataspace(std::span<const hsize_t>(&n, 1));
  Check(
      H5Dwrite(dataset, mem_type, mem_space.get(), file_space.get(), H5P_DEFAULT, gathered.data()),
      "H5Dwrite(cells) " + ObjectName(dataset));
}

void WriteStrings(hid_t parent, const std::string& name, const std::vector<std::string>& v) {
  Id type = StringType();
  const hsize_t n = v.size();
  std::vector<const char*> ptrs;
  for (const std::string& s : v) {
    ptrs.push_back(s.c_str());
  }
  Id ds = CreateDataset(parent, name, type.get(), std::span<const hsize_t>(&n, 1), {}, 0, nullptr);
  WriteAll(ds.get(), type.get(), ptrs.data());
}

std::vector<std::string> ReadStrings(hid_t dataset) {
  const std::vector<hsize_t> shape = Shape(dataset);
  const std::size_t n = shape.empty() ? 1 : static_cast<std::size_t>(shape[0]);
  Id type = StringType();
  std::vector<char*> ptrs(n, nullptr);
  ReadAll(dataset, type.get(), ptrs.data());
  std::vector<std::string> out;
  for (char* p : ptrs) {
    out.emplace_back(p != nullptr ? p : "");
  }
  Id space(H5Dget_space(dataset), H5Sclose, "H5Dget_space");
  H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, ptrs.data());
  return out;
}

namespace {

Id CreateAttr(hid_t obj, const std::string& name, hid_t type, hid_t space) {
  if (Check(H5Aexists(obj, name.c_str()), "H5Aexists " + name) > 0) {
    Check(H5Adelete(obj, name.c_str()), "H5Adelete " + name);
  }
  return Id(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
            "create attribute " + name);
}

Id Scalar() { return Id(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate(scalar)"); }

Id OpenAttr(hid_t obj, const std::string& name) {
  return Id(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
}

std::size_t AttrCount(hid_t attr) {
  Id space(H5Aget_space(attr), H5Sclose, "H5Aget_space");
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  Check(n < 0 ? -1 : 0, "H5Sget_simple_extent_npoints");
  return static_cast<std::size_t>(n);
}

}  // namespace

void SetAttr(hid_t obj, const std::string& name, const std::string& value) {
  Id type = StringType();
  Id attr = CreateAttr(obj, name, type.get(), Scalar().get());
  const char* p = value.c_str();
  Check(H5Awrite(attr.get(), type.get(), &p), "write attribute " + name);
}

void SetAttr(hid_t obj, const std::string& name, std::int64_t value) {
  // An existing integer attribute is rewritten in place (a resume's run counter), which
  // touches no attribute index of the object.
  if (Check(H5Aexists(obj, name.c_str()), "H5Aexists " + name) > 0) {
    Id old = OpenAttr(obj, name);
    Id type(H5Aget_type(old.get()), H5Tclose, "H5Aget_type " + name);
    if (H5Tget_class(type.get()) == H5T_INTEGER && AttrCount(old.get()) == 1) {
      Check(H5Awrite(old.get(), H5T_NATIVE_INT64, &value), "write attribute " + name);
      return;
    }
  }
  Id attr = CreateAttr(obj, name, H5T_STD_I64LE, Scalar().get());
  Check(H5Awrite(attr.get(), H5T_NATIVE_INT64, &value), "write attribute " + name);
}

void SetAttr(hid_t obj, const std::string& name, double value) {
  Id attr = CreateAttr(obj, name, H5T_IEEE_F64LE, Scalar().get());
  Check(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &value), "write attribute " + name);
}

void SetAttr(hid_t obj, const std::string& name, const std::vector<std::string>& values) {
  Id type = StringType();
  const hsize_t n = values.size();
  Id attr = CreateAttr(obj, name, type.get(), Dataspace(std::span<const hsize_t>(&n, 1)).get());
  std::vector<const char*> ptrs;
  for (const std::string& s : values) {
    ptrs.push_back(s.c_str());
  }
  // An empty list (a fit over no other axis) is an attribute of no element: nothing to write.
  if (n == 0) return;
  Check(H5Awrite(attr.get(), type.get(), ptrs.data()), "write attribute " + name);
}

void SetAttr(hid_t obj, const std::string& name, const std::vector<std::int32_t>& values) {
  const hsize_t n = values.size();
  Id attr = CreateAttr(obj, name, H5T_STD_I32LE, Dataspace(std::span<const hsize_t>(&n, 1)).get());
  Check(H5Awrite(attr.get(), H5T_NATIVE_INT32, values.data()), "write attribute " + name);
}

std::string GetStringAttr(hid_t obj, const std::string& name) {
  Id attr = OpenAttr(obj, name);
  Id type = StringType();
  char* p = nullptr;
  Check(H5Aread(attr.get(), type.get(), &p), "read attribute " + name);
  std::string out = p != nullptr ? p : "";
  H5free_memory(p);
  return out;
}

std::int64_t GetIntAttr(hid_t obj, const std::string& name) {
  Id attr = OpenAttr(obj, name);
  std::int64_t v = 0;
  Check(H5Aread(attr.get(), H5T_NATIVE_INT64, &v), "read attribute " + name);
  return v;
}

double GetDoubleAttr(hid_t obj, const std::string& name) {
  Id attr = OpenAttr(obj, name);
  double v = 0.0;
  Check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &v), "read attribute " + name);
  return v;
}

bool IsStringAttr(hid_t obj, const std::string& name) {
  Id attr = OpenAttr(obj, name);
  Id type(H5Aget_type(attr.get()), H5Tclose, "H5Aget_type " + name);
  return H5Tget_class(type.get()) == H5T_STRING;
}

std::vector<std::string> GetStringListAttr(hid_t obj, const std::string& name) {
  Id attr = OpenAttr(obj, name);
  Id type = StringType();
  std::vector<char*> ptrs(AttrCount(attr.get()), nullptr);
  Check(H5Aread(attr.get(), type.get(), ptrs.data()), "read attribute " + name);
  std::vector<std::string> out;
  for (char* p : ptrs) {
    out.emplace_back(p != nullptr ? p : "");
    H5free_memory(p);
  }
  return out;
}

std::vector<std::int32_t> GetIntListAttr(hid_t obj, const std::string& name) {
  Id attr = OpenAttr(obj, name);
  std::vector<std::int32_t> out(AttrCount(attr.get()));
  Check(H5Aread(attr.get(), H5T_NATIVE_INT32, out.data()), "read attribute " + name);
  return out;
}

bool HasAttr(hid_t obj, const std::string& name) {
  return Check(H5Aexists(obj, name.c_str()), "H5Aexists " + name) > 0;
}

void SetScale(hid_t scale, const std::string& name) {
  Check(H5DSset_scale(scale, name.c_str()), "H5DSset_scale " + name);
}

void AttachScale(hid_t dataset, hid_t scale, unsigned dim, const std::string& label) {
  Check(H5DSattach_scale(dataset, scale, dim), "H5DSattach_scale " + label);
  Check(H5DSset_label(dataset, dim, label.c_str()), "H5DSset_label " + label);
}

namespace {

// Reads every attribute of one object (the attribute heaps and indexes of the 1.8 format are
// checksummed, so damage shows here rather than when a writer first touches them).
herr_t ReadAttribute(hid_t obj, const char* name, const H5A_info_t* /*info*/, void* /*data*/) {
  Id attr = OpenAttr(obj, name);
  Id file_type(H5Aget_type(attr.get()), H5Tclose, std::string("H5Aget_type ") + name);
  Id type(H5Tget_native_type(file_type.get(), H5T_DIR_ASCEND), H5Tclose,
          std::string("H5Tget_native_type ") + name);
  Id space(H5Aget_space(attr.get()), H5Sclose, std::string("H5Aget_space ") + name);
  const std::size_t n = std::max<std::size_t>(1, AttrCount(attr.get()));
  std::vector<unsigned char> buffer(n * H5Tget_size(type.get()));
  Check(H5Aread(attr.get(), type.get(), buffer.data()), std::string("read attribute ") + name);
  if (H5Tdetect_class(type.get(), H5T_VLEN) > 0 || H5Tis_variable_str(type.get()) > 0) {
    H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, buffer.data());
  }
  return 0;
}

herr_t ReadObjectAttributes(hid_t root, const char* name, const H5O_info_t* /*info*/,
                            void* /*data*/) {
  Id obj(H5Oopen(root, name, H5P_DEFAULT), H5Oclose, std::string("open object ") + name);
  hsize_t at = 0;
  return H5Aiterate2(obj.get(), H5_INDEX_NAME, H5_ITER_INC, &at, ReadAttribute, nullptr);
}

}  // namespace

void ReadAllMetadata(hid_t file) {
  Check(H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC, ReadObjectAttributes, nullptr, H5O_INFO_BASIC),
        "H5Ovisit (every object and attribute)");
}

void FlushToDisk(hid_t file) {
  Check(H5Fflush(file, H5F_SCOPE_GLOBAL), "H5Fflush");
  void* handle = nullptr;
  Check(H5Fget_vfd_handle(file, H5P_DEFAULT, &handle), "H5Fget_vfd_handle");
  if (handle != nullptr && ::fsync(*static_cast<int*>(handle)) != 0) {
    throw H5Error(std::string("fsync: ") + std::strerror(errno));
  }
}

}  // namespace skewbridge::jobs::h5
