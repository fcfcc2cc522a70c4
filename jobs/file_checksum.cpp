#include "jobs/file_checksum.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <memory>

#include "solver/common/error.h"
#include "solver/common/file_kind.h"

namespace skewbridge::jobs {
namespace {

using DigestContext = std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)>;

DigestContext NewContext() {
  DigestContext ctx(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (ctx == nullptr || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256: cannot initialise the digest");
  }
  return ctx;
}

std::string Finish(EVP_MD_CTX* ctx) {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int size = 0;
  if (EVP_DigestFinal_ex(ctx, digest.data(), &size) != 1) {
    throw std::runtime_error("SHA-256: cannot finish the digest");
  }
  std::string hex;
  hex.reserve(2 * size);
  for (unsigned int i = 0; i < size; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

}  // namespace

FileChecksum ChecksumFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError::AtLine(path.string(), 0, WhyUnreadable(path));
  }
  DigestContext ctx = NewContext();
  // Uninitialised: zeroing a block costs as much as hashing it, and most records are smaller.
  constexpr std::size_t kBlock = std::size_t{1} << 16;
  const auto block = std::make_unique_for_overwrite<char[]>(kBlock);
  FileChecksum out;
  while (in) {
    in.read(block.get(), static_cast<std::streamsize>(kBlock));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got > 0 && EVP_DigestUpdate(ctx.get(), block.get(), got) != 1) {
      throw std::runtime_error("SHA-256: cannot update the digest");
    }
    out.bytes += got;
  }
  if (in.bad()) {
    throw InputError::AtLine(path.string(), 0, "read error while checksumming the file");
  }
  out.sha256 = Finish(ctx.get());
  return out;
}

std::string Sha256Hex(std::string_view bytes) {
  DigestContext ctx = NewContext();
  if (EVP_DigestUpdate(ctx.get(), bytes.data(), bytes.size()) != 1) {
    throw std::runtime_error("SHA-256: cannot update the digest");
  }
  return Finish(ctx.get());
}

}  // namespace skewbridge::jobs
