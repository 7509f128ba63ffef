// CurveZMQ keys for the probe stream: key pairs as Z85 text files, and the sets of keys a server
// admits. `ddish keys --out DIR --name NAME` writes DIR/NAME.key (the secret key, mode 0600) and
// DIR/NAME.pub (the public key); a secret key file is all a side needs of its own pair (the
// public key follows from it), a .pub file is what the other side is given.
#pragma once

#include <filesystem>
#include <set>
#include <string>

namespace ddish::net {

struct CurveKeyPair {
  std::string public_z85;  // 40 characters
  std::string secret_z85;
};

// A fresh key pair (libzmq's CURVE, libsodium's randomness). Throws std::runtime_error when the
// library was built without CURVE.
CurveKeyPair generate_curve_keys();

// Writes NAME.key (0600) and NAME.pub into dir (created); returns the two paths' stem.
void write_curve_keys(const std::filesystem::path& dir, const std::string& name, const CurveKeyPair& keys);

// Reads a secret key file (.key) and derives its public key; or a public key file (.pub).
// Throws std::runtime_error naming the file for anything that is not one Z85 key of 40 chars.
CurveKeyPair read_secret_key(const std::filesystem::path& file);
std::string read_public_key(const std::filesystem::path& file);

// Every *.pub file of dir: the client keys a server admits. Throws when dir holds none.
std::set<std::string> read_allowed_keys(const std::filesystem::path& dir);

}  // namespace ddish::net
