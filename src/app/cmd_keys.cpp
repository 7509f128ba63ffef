// ddish keys --out DIR [--name NAME]
//
// Makes a CurveZMQ key pair for `ddish serve` / `ddish view` (net/curve_keys.h): DIR/NAME.key
// holds the secret key (mode 0600, give it to --curve-secret), DIR/NAME.pub the public key (a
// server's goes to its clients' --curve-server-key, a client's into the server's --allow-keys
// folder). Z85 text, one key per file.
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "net/curve_keys.h"

namespace ddish::app {
namespace {

struct KeysArgs {
  std::string out;
  std::string name = "ddish";
};

int run_keys(const KeysArgs& a) {
  if (a.name.empty() || a.name.find('/') != std::string::npos)
    throw std::invalid_argument("--name must be a file name without '/'");
  const net::CurveKeyPair keys = net::generate_curve_keys();
  net::write_curve_keys(a.out, a.name, keys);
  const std::filesystem::path dir(a.out);
  std::printf("wrote %s (secret)\nwrote %s (public %s)\n", (dir / (a.name + ".key")).string().c_str(),
              (dir / (a.name + ".pub")).string().c_str(), keys.public_z85.c_str());
  return 0;
}

Action make_keys(CLI::App& root) {
  auto a = std::make_shared<KeysArgs>();
  CLI::App* cmd = root.add_subcommand("keys", "CurveZMQ key pair for ddish serve / ddish view");
  cmd->add_option("--out", a->out, "directory to write NAME.key (secret) and NAME.pub (public) into")->required();
  cmd->add_option("--name", a->name, "file name of the pair")->capture_default_str();
  return [a]() { return run_keys(*a); };
}

}  // namespace

DDISH_COMMAND(62, make_keys);

}  // namespace ddish::app
