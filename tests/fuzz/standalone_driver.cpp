// Runs a fuzz target without libFuzzer (the g++ build, under CTest): every file of the corpus
// folders, then a fixed number of inputs mutated from them with a fixed seed, so the run is
// bounded and repeatable. A finding aborts the process (fuzz_support.h), which fails the test;
// the input that found it is written first to fuzz-crash-TARGET-N for the regression corpus.
//
//   fuzz_NAME [--mutations N] [--seed S] [--max-len BYTES] CORPUS_DIR_OR_FILE...
//
// The mutations are libFuzzer's simplest ones (bit flips, byte changes, interesting integers,
// inserted and erased runs, copies within the input, splices of two inputs, ASCII digits in
// place of digits); without coverage feedback they stay near the seeds, which is what a
// seconds-long smoke test is for. Real campaigns: scripts/fuzz.sh.
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

Bytes read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The input under test: the SIGABRT handler writes it out when a finding aborts.
const Bytes* g_current = nullptr;

void run_one(const Bytes& input) {
  g_current = &input;
  // A copy of exactly the input's size, so that reads past the end are caught by sanitizers.
  std::vector<std::uint8_t> copy(input);
  LLVMFuzzerTestOneInput(copy.empty() ? nullptr : copy.data(), copy.size());
  g_current = nullptr;
}

void on_abort(int) {
  if (g_current) {
    const std::string name = "fuzz-crash-" + std::to_string(::getpid());
    if (std::FILE* f = std::fopen(name.c_str(), "wb")) {
      std::fwrite(g_current->data(), 1, g_current->size(), f);
      std::fclose(f);
      std::fprintf(stderr, "standalone driver: the input is in %s (%zu bytes)\n", name.c_str(),
                   g_current->size());
    }
  }
  std::signal(SIGABRT, SIG_DFL);
}

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  Bytes mutate(const std::vector<Bytes>& corpus, std::size_t max_len) {
    Bytes b = corpus[pick(corpus.size())];
    const int steps = 1 + int(pick(4));
    for (int s = 0; s < steps; ++s) step(b, corpus);
    if (b.size() > max_len) b.resize(max_len);
    return b;
  }

 private:
  std::size_t pick(std::size_t n) { return n == 0 ? 0 : std::size_t(rng_() % n); }

  void step(Bytes& b, const std::vector<Bytes>& corpus) {
    static const std::uint64_t interesting[] = {0,         1,          0x7f,       0x80,
                                                0xff,      0x7fff,     0x8000,     0xffff,
                                                0x7fffffff, 0x80000000, 0xffffffff, 0x100000000ull};
    switch (pick(b.empty() ? 3 : 9)) {
      case 0: {  // insert a run of one byte
        const std::size_t at = pick(b.size() + 1);
        b.insert(b.begin() + std::ptrdiff_t(at), 1 + pick(8), std::uint8_t(rng_()));
        break;
      }
      case 1: {  // splice: the head of this input, the tail of another
        const Bytes& o = corpus[pick(corpus.size())];
        const std::size_t cut = pick(b.size() + 1), from = pick(o.size() + 1);
        b.resize(cut);
        b.insert(b.end(), o.begin() + std::ptrdiff_t(from), o.end());
        break;
      }
      case 2: {  // an interesting integer, little-endian, 1 to 8 bytes
        const std::uint64_t v = interesting[pick(std::size(interesting))];
        const std::size_t n = 1 + pick(8), at = pick(b.size() + 1);
        for (std::size_t i = 0; i < n; ++i)
          b.insert(b.begin() + std::ptrdiff_t(at + i), std::uint8_t(v >> (8 * (i % 8))));
        break;
      }
      case 3: b[pick(b.size())] ^= std::uint8_t(1u << pick(8)); break;  // flip a bit
      case 4: b[pick(b.size())] = std::uint8_t(rng_()); break;           // any byte
      case 5: {  // erase a run
        const std::size_t at = pick(b.size()), n = 1 + pick(std::min<std::size_t>(64, b.size() - at));
        b.erase(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + n));
        break;
      }
      case 6: {  // copy a run elsewhere (overwriting)
        const std::size_t from = pick(b.size()), to = pick(b.size());
        const std::size_t n = std::min({1 + pick(32), b.size() - from, b.size() - to});
        std::memmove(b.data() + to, b.data() + from, n);
        break;
      }
      case 7: b.resize(pick(b.size() + 1)); break;  // truncate
      case 8: {  // a digit of a JSON number changed, or a big number put in
        std::vector<std::size_t> digits;
        for (std::size_t i = 0; i < b.size(); ++i)
          if (b[i] >= '0' && b[i] <= '9') digits.push_back(i);
        if (digits.empty()) break;
        const std::size_t at = digits[pick(digits.size())];
        static const char* numbers[] = {"0", "-1", "1e39", "4294967296", "2147483648", "1e-45",
                                        "9999999", "-0", "65536", "1.5"};
        const std::string n = pick(2) ? std::string(1, char('0' + pick(10))) : numbers[pick(10)];
        b.erase(b.begin() + std::ptrdiff_t(at));
        b.insert(b.begin() + std::ptrdiff_t(at), n.begin(), n.end());
        break;
      }
    }
  }

  std::mt19937_64 rng_;
};

}  // namespace

int main(int argc, char** argv) {
  long mutations = 1000;
  std::uint64_t seed = 1;
  std::size_t max_len = 1 << 20;
  std::vector<fs::path> inputs;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--mutations" || a == "--seed" || a == "--max-len") && i + 1 < argc) {
      const long long v = std::atoll(argv[++i]);
      if (a == "--mutations") mutations = long(v);
      if (a == "--seed") seed = std::uint64_t(v);
      if (a == "--max-len") max_len = std::size_t(v);
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "usage: %s [--mutations N] [--seed S] [--max-len BYTES] CORPUS...\n", argv[0]);
      return 2;
    } else {
      inputs.emplace_back(a);
    }
  }
  std::vector<Bytes> corpus;
  for (const fs::path& p : inputs) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(p))
        if (e.is_regular_file()) files.push_back(e.path());
      std::sort(files.begin(), files.end());  // a repeatable order
      for (const fs::path& f : files) corpus.push_back(read_file(f));
    } else if (fs::is_regular_file(p, ec)) {
      corpus.push_back(read_file(p));
    } else {
      std::fprintf(stderr, "standalone driver: no such corpus: %s\n", p.c_str());
      return 2;
    }
  }
  if (corpus.empty()) {
    std::fprintf(stderr, "standalone driver: the corpus is empty\n");
    return 2;
  }
  std::signal(SIGABRT, on_abort);
  for (const Bytes& b : corpus) run_one(b);
  run_one({});  // the empty input
  Mutator mutator(seed);
  for (long k = 0; k < mutations; ++k) run_one(mutator.mutate(corpus, max_len));
  std::printf("%zu corpus inputs, the empty input and %ld mutated inputs (seed %llu): no finding\n",
              corpus.size(), mutations, static_cast<unsigned long long>(seed));
  return 0;
}
