// A main() for the fuzz targets in builds without libFuzzer (GCC, the sanitizer suite): runs
// every file of a seed corpus through LLVMFuzzerTestOneInput, then `iterations` inputs made
// from them by random byte edits (fixed seed: the same inputs every run, so a failure
// reproduces). Not coverage-guided: scripts/fuzz.sh builds the same targets with clang's
// libFuzzer for real fuzzing sessions.
//   usage: fuzz_<target> CORPUS_DIR ITERATIONS
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_input.h"

namespace {

struct SplitMix64 {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  size_t below(size_t n) { return n == 0 ? 0 : size_t(next() % n); }
};

// Tokens that parsers trip over, for text and binary formats alike.
const char* const kTokens[] = {"-1", "0", "nan", "inf", "1e39", "-0", "4294967296", "18446744073709551616",
                               "\"", "<", "/>", "&", "$", "\n", " ", "#", "/", "//", "\xff\xff\xff\xff"};

std::vector<uint8_t> mutate(const std::vector<std::vector<uint8_t>>& corpus, SplitMix64& rng) {
  std::vector<uint8_t> s = corpus[rng.below(corpus.size())];
  const int edits = 1 + int(rng.below(4));
  for (int e = 0; e < edits; ++e) {
    const size_t at = rng.below(s.size() + 1);
    switch (rng.below(6)) {
      case 0:  // flip a bit
        if (!s.empty()) s[rng.below(s.size())] ^= uint8_t(1u << rng.below(8));
        break;
      case 1:  // a random byte
        s.insert(s.begin() + ptrdiff_t(at), uint8_t(rng.next()));
        break;
      case 2:  // delete a run
        if (!s.empty()) {
          const size_t n = std::min(s.size() - std::min(at, s.size() - 1), 1 + rng.below(16));
          const size_t from = std::min(at, s.size() - 1);
          s.erase(s.begin() + ptrdiff_t(from), s.begin() + ptrdiff_t(from + n));
        }
        break;
      case 3: {  // a token
        const std::string t = kTokens[rng.below(std::size(kTokens))];
        s.insert(s.begin() + ptrdiff_t(at), t.begin(), t.end());
        break;
      }
      case 4: {  // duplicate a run
        if (s.empty()) break;
        const size_t from = rng.below(s.size()), n = std::min(s.size() - from, 1 + rng.below(64));
        std::vector<uint8_t> run(s.begin() + ptrdiff_t(from), s.begin() + ptrdiff_t(from + n));
        s.insert(s.begin() + ptrdiff_t(std::min(at, s.size())), run.begin(), run.end());
        break;
      }
      default: {  // splice in a piece of another corpus entry
        const std::vector<uint8_t>& other = corpus[rng.below(corpus.size())];
        if (other.empty()) break;
        const size_t from = rng.below(other.size()), n = std::min(other.size() - from, 1 + rng.below(256));
        s.insert(s.begin() + ptrdiff_t(std::min(at, s.size())), other.begin() + ptrdiff_t(from),
                 other.begin() + ptrdiff_t(from + n));
        break;
      }
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR ITERATIONS\n", argv[0]);
    return 2;
  }
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(argv[1]))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<std::vector<uint8_t>> corpus;
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    corpus.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (corpus.empty()) {
    std::fprintf(stderr, "%s: empty corpus\n", argv[1]);
    return 2;
  }
  for (const auto& input : corpus) LLVMFuzzerTestOneInput(input.data(), input.size());
  SplitMix64 rng{0x5eed};
  const long iterations = std::atol(argv[2]);
  for (long i = 0; i < iterations; ++i) {
    const std::vector<uint8_t> input = mutate(corpus, rng);
    LLVMFuzzerTestOneInput(input.data(), input.size());
  }
  std::printf("%zu corpus inputs and %ld mutated ones, no crash\n", corpus.size(), iterations);
  std::error_code ignored;
  std::filesystem::remove_all(erpt::fuzz::scratchDir(), ignored);
  return 0;
}
