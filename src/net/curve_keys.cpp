#include "net/curve_keys.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <zmq.h>

#include "io/atomic_file.h"

namespace ddish::net {
namespace {

std::string read_key_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read key file " + file.string());
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  std::uint8_t binary[32];
  if (text.size() != 40 || zmq_z85_decode(binary, text.c_str()) == nullptr)
    throw std::runtime_error(file.string() + " is not a CurveZMQ key (40 Z85 characters)");
  return text;
}

// Written whole or not at all (io/atomic_file.h). A secret key's file is created owner-only
// before a byte of the key is in it, so it is never readable by others, not even for a moment.
void write_text(const std::filesystem::path& file, const std::string& text, bool secret) {
  io::write_atomically(file, [&](const std::filesystem::path& temporary) {
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, secret ? 0600 : 0644);
    if (fd < 0) throw std::runtime_error(std::strerror(errno));
    if (secret) ::fchmod(fd, 0600);  // whatever the umask
    const std::string line = text + '\n';
    const ssize_t n = ::write(fd, line.data(), line.size());
    const int write_errno = errno;
    ::close(fd);
    if (n != static_cast<ssize_t>(line.size()))
      throw std::runtime_error(n < 0 ? std::strerror(write_errno) : "short write");
  });
}

}  // namespace

CurveKeyPair generate_curve_keys() {
  if (!zmq_has("curve")) throw std::runtime_error("this libzmq was built without CURVE");
  char public_key[41], secret_key[41];
  if (zmq_curve_keypair(public_key, secret_key) != 0)
    throw std::runtime_error(std::string("zmq_curve_keypair: ") + zmq_strerror(zmq_errno()));
  return {public_key, secret_key};
}

void write_curve_keys(const std::filesystem::path& dir, const std::string& name, const CurveKeyPair& keys) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir)) throw std::runtime_error("cannot create directory " + dir.string());
  write_text(dir / (name + ".key"), keys.secret_z85, true);
  write_text(dir / (name + ".pub"), keys.public_z85, false);
}

CurveKeyPair read_secret_key(const std::filesystem::path& file) {
  CurveKeyPair k;
  k.secret_z85 = read_key_text(file);
  char public_key[41];
  if (zmq_curve_public(public_key, k.secret_z85.c_str()) != 0)
    throw std::runtime_error(file.string() + ": cannot derive the public key");
  k.public_z85 = public_key;
  return k;
}

std::string read_public_key(const std::filesystem::path& file) { return read_key_text(file); }

std::set<std::string> read_allowed_keys(const std::filesystem::path& dir) {
  std::set<std::string> keys;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".pub") keys.insert(read_key_text(e.path()));
  if (ec) throw std::runtime_error("cannot read --allow-keys directory " + dir.string());
  if (keys.empty()) throw std::runtime_error("--allow-keys " + dir.string() + " holds no .pub key");
  return keys;
}

}  // namespace ddish::net
