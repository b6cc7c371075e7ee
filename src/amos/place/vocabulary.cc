#include "amos/place/vocabulary.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <set>

#include "amos/core/binary_stream.h"
#include "amos/core/error.h"
#include "amos/core/option_error.h"
#include "amos/feature/descriptor_distance.h"
#include "amos/io/atomic_file.h"

namespace amos::place {

namespace {

constexpr char kMagic[8] = {'A', 'M', 'O', 'S', 'V', 'O', 'C', '\0'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 8 + 6 * 4;
constexpr int kBytes = 32;

using Descriptor = std::array<std::uint8_t, kBytes>;

int distance(const std::uint8_t* a, const std::uint8_t* b) { return feature::hammingDistance(a, b); }

// The bitwise majority of the descriptors (a bit is set when more than half of them have it).
Descriptor majority(const std::vector<const std::uint8_t*>& members) {
  std::array<int, kBytes * 8> counts{};
  for (const std::uint8_t* d : members) {
    for (int byte = 0; byte < kBytes; ++byte) {
      for (int bit = 0; bit < 8; ++bit) counts[byte * 8 + bit] += (d[byte] >> bit) & 1;
    }
  }
  Descriptor out{};
  const int n = static_cast<int>(members.size());
  for (int byte = 0; byte < kBytes; ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      if (2 * counts[byte * 8 + bit] > n) out[byte] = static_cast<std::uint8_t>(out[byte] | (1u << bit));
    }
  }
  return out;
}

// k-majority clustering of `descs` into at most k groups (k-means++ seeding; empty groups are dropped).
std::vector<std::vector<const std::uint8_t*>> kMajority(const std::vector<const std::uint8_t*>& descs, int k,
                                                        int iterations, std::mt19937& rng,
                                                        std::vector<Descriptor>& centres) {
  centres.clear();
  const std::size_t n = descs.size();
  std::vector<double> nearest(n, std::numeric_limits<double>::max());
  std::size_t pick = std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  while (static_cast<int>(centres.size()) < k) {
    Descriptor c;
    std::memcpy(c.data(), descs[pick], kBytes);
    centres.push_back(c);
    double total = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double d = distance(descs[i], c.data());
      nearest[i] = std::min(nearest[i], d * d);
      total += nearest[i];
    }
    if (total <= 0) break;  // every descriptor equals a centre already
    double r = std::uniform_real_distribution<double>(0, total)(rng);
    pick = n - 1;
    for (std::size_t i = 0; i < n; ++i) {
      r -= nearest[i];
      if (r <= 0) {
        pick = i;
        break;
      }
    }
  }
  std::vector<int> assignment(n, -1);
  std::vector<std::vector<const std::uint8_t*>> groups;
  for (int it = 0; it < iterations; ++it) {
    bool changed = false;
    groups.assign(centres.size(), {});
    for (std::size_t i = 0; i < n; ++i) {
      int best = 0, best_d = std::numeric_limits<int>::max();
      for (std::size_t c = 0; c < centres.size(); ++c) {
        const int d = distance(descs[i], centres[c].data());
        if (d < best_d) {
          best_d = d;
          best = static_cast<int>(c);
        }
      }
      changed |= assignment[i] != best;
      assignment[i] = best;
      groups[best].push_back(descs[i]);
    }
    if (!changed) break;
    for (std::size_t c = 0; c < centres.size(); ++c) {
      if (!groups[c].empty()) centres[c] = majority(groups[c]);
    }
  }
  std::vector<std::vector<const std::uint8_t*>> kept;
  std::vector<Descriptor> kept_centres;
  for (std::size_t c = 0; c < centres.size(); ++c) {
    if (groups[c].empty()) continue;
    kept.push_back(std::move(groups[c]));
    kept_centres.push_back(centres[c]);
  }
  centres = std::move(kept_centres);
  return kept;
}

}  // namespace

double similarity(const BowVector& a, const BowVector& b) {
  double s = 0;
  auto i = a.words.begin();
  auto j = b.words.begin();
  while (i != a.words.end() && j != b.words.end()) {
    if (i->first < j->first) {
      ++i;
    } else if (j->first < i->first) {
      ++j;
    } else {
      s += std::abs(i->second) + std::abs(j->second) - std::abs(i->second - j->second);
      ++i;
      ++j;
    }
  }
  return 0.5 * s;
}

void VocabularyOptions::check() const {
  core::requireAtLeast(branching, "branching", 2);
  core::requireAtLeast(depth, "depth", 1);
  core::requireAtLeast(iterations, "iterations", 1);
  core::requireOption(std::pow(branching, depth) <= 1e7, core::option(depth, "depth"),
                      fmt::format("branching^depth = {}^{} words is too many (at most 10^7)", branching, depth));
}

Vocabulary Vocabulary::train(const std::vector<cv::Mat>& images, const VocabularyOptions& options) {
  options.check();
  std::vector<const std::uint8_t*> all;
  for (const cv::Mat& d : images) {
    core::require(d.empty() || (d.type() == CV_8U && d.cols == kBytes),
                  "Vocabulary::train: descriptors must be N x 32 CV_8U");
    for (int r = 0; r < d.rows; ++r) all.push_back(d.ptr<std::uint8_t>(r));
  }
  core::require(!all.empty(), "Vocabulary::train: no training descriptors");
  Vocabulary v;
  v.branching_ = options.branching;
  v.depth_ = options.depth;
  std::mt19937 rng(options.seed);
  v.nodes_.emplace_back();
  // Depth-first: a node's children are appended together (contiguous), then each is split in turn.
  struct Work {
    std::uint32_t node;
    int level;
    std::vector<const std::uint8_t*> descs;
  };
  std::vector<Work> stack;
  stack.push_back({0, 0, std::move(all)});
  while (!stack.empty()) {
    Work w = std::move(stack.back());
    stack.pop_back();
    if (w.level == options.depth || w.descs.size() <= 1) continue;  // a leaf
    std::vector<Descriptor> centres;
    std::vector<std::vector<const std::uint8_t*>> groups;
    if (static_cast<int>(w.descs.size()) <= options.branching) {
      for (const std::uint8_t* d : w.descs) {
        Descriptor c;
        std::memcpy(c.data(), d, kBytes);
        centres.push_back(c);
        groups.push_back({d});
      }
    } else {
      groups = kMajority(w.descs, options.branching, options.iterations, rng, centres);
    }
    const auto first = static_cast<std::uint32_t>(v.nodes_.size());
    v.nodes_[w.node].first_child = first;
    v.nodes_[w.node].num_children = static_cast<std::uint32_t>(centres.size());
    for (const Descriptor& c : centres) {
      Node child;
      child.descriptor = c;
      v.nodes_.push_back(child);
    }
    // Pushed in reverse so the first child is split first (node order = depth-first order of the children).
    for (std::size_t c = groups.size(); c-- > 0;) {
      stack.push_back({first + static_cast<std::uint32_t>(c), w.level + 1, std::move(groups[c])});
    }
  }
  WordId next = 0;
  for (Node& node : v.nodes_) {
    if (node.num_children == 0) node.word = next++;
  }
  // idf over the training images.
  std::vector<int> images_with(next, 0);
  for (const cv::Mat& d : images) {
    std::set<WordId> seen;
    for (int r = 0; r < d.rows; ++r) seen.insert(v.word(d.ptr<std::uint8_t>(r)));
    for (const WordId w : seen) ++images_with[w];
  }
  v.idf_.resize(next);
  const double n_images = static_cast<double>(images.size());
  for (WordId w = 0; w < next; ++w) {
    v.idf_[w] = static_cast<float>(std::log(n_images / std::max(1, images_with[w])));
  }
  return v;
}

WordId Vocabulary::word(const std::uint8_t* descriptor) const {
  std::uint32_t node = 0;
  while (nodes_[node].num_children > 0) {
    const Node& parent = nodes_[node];
    std::uint32_t best = parent.first_child;
    int best_d = std::numeric_limits<int>::max();
    for (std::uint32_t c = parent.first_child; c < parent.first_child + parent.num_children; ++c) {
      const int d = distance(descriptor, nodes_[c].descriptor.data());
      if (d < best_d) {
        best_d = d;
        best = c;
      }
    }
    node = best;
  }
  return nodes_[node].word;
}

BowVector Vocabulary::transform(const cv::Mat& descriptors) const {
  BowVector out;
  if (empty() || descriptors.empty()) return out;
  std::vector<WordId> words(descriptors.rows);
  for (int r = 0; r < descriptors.rows; ++r) words[r] = word(descriptors.ptr<std::uint8_t>(r));
  std::sort(words.begin(), words.end());
  double total = 0;
  for (std::size_t i = 0; i < words.size();) {
    std::size_t j = i;
    while (j < words.size() && words[j] == words[i]) ++j;
    const float weight = static_cast<float>(j - i) * idf_[words[i]];
    // A word every training image had (idf 0) says nothing about the place.
    if (weight > 0) {
      out.words.emplace_back(words[i], weight);
      total += weight;
    }
    i = j;
  }
  if (total > 0) {
    for (auto& [w, x] : out.words) x = static_cast<float>(x / total);
  }
  return out;
}

std::string Vocabulary::encode() const {
  core::ByteWriter body;
  for (const Node& n : nodes_) {
    body.putBytes(n.descriptor.data(), kBytes);
    body.put(n.first_child);
    body.put(n.num_children);
    body.put(n.word);
  }
  for (const float x : idf_) body.put(x);
  core::ByteWriter file;
  file.putBytes(kMagic, sizeof(kMagic));
  file.put(kVersion);
  file.put(static_cast<std::uint32_t>(branching_));
  file.put(static_cast<std::uint32_t>(depth_));
  file.put(static_cast<std::uint32_t>(nodes_.size()));
  file.put(static_cast<std::uint32_t>(idf_.size()));
  file.put(core::crc32(body.bytes()));
  file.bytes() += body.bytes();
  return std::move(file.bytes());
}

Vocabulary Vocabulary::decode(const std::string& bytes, const std::string& source) {
  auto fail = [&](const std::string& problem) { throw core::Error(source + ": " + problem); };
  if (bytes.size() < kHeaderBytes) fail(fmt::format("not a vocabulary file or truncated: {} bytes", bytes.size()));
  core::ByteReader h(std::string_view(bytes.data(), kHeaderBytes), source);
  char magic[8];
  h.getBytes(magic, sizeof(magic), "magic");
  if (!std::equal(std::begin(magic), std::end(magic), std::begin(kMagic))) {
    fail("not an Amos-SLAM vocabulary file (it does not start with \"AMOSVOC\")");
  }
  const auto version = h.get<std::uint32_t>("version");
  if (version != kVersion) fail(fmt::format("vocabulary format version {}, this program reads {}", version, kVersion));
  Vocabulary v;
  v.branching_ = static_cast<int>(h.get<std::uint32_t>("branching"));
  v.depth_ = static_cast<int>(h.get<std::uint32_t>("depth"));
  const auto n_nodes = h.get<std::uint32_t>("node count");
  const auto n_words = h.get<std::uint32_t>("word count");
  const auto checksum = h.get<std::uint32_t>("checksum");
  const std::size_t body_bytes = static_cast<std::size_t>(n_nodes) * (kBytes + 12) + std::size_t{n_words} * 4;
  if (bytes.size() - kHeaderBytes != body_bytes) {
    fail(fmt::format("truncated or corrupt: {} nodes and {} words need {} bytes after the header, the file has {}",
                     n_nodes, n_words, body_bytes, bytes.size() - kHeaderBytes));
  }
  const std::string_view body(bytes.data() + kHeaderBytes, body_bytes);
  if (core::crc32(body) != checksum) fail("corrupt: checksum mismatch");
  core::ByteReader r(body, source);
  v.nodes_.resize(n_nodes);
  std::uint32_t words = 0;
  for (std::uint32_t i = 0; i < n_nodes; ++i) {
    Node& n = v.nodes_[i];
    r.getBytes(n.descriptor.data(), kBytes, "node");
    n.first_child = r.get<std::uint32_t>("node");
    n.num_children = r.get<std::uint32_t>("node");
    n.word = r.get<WordId>("node");
    const bool leaf = n.num_children == 0;
    if ((leaf && n.word >= n_words) || (!leaf && (n.word != kNoWord || n.first_child <= i ||
                                                  std::uint64_t{n.first_child} + n.num_children > n_nodes))) {
      fail(fmt::format("malformed: node {}", i));
    }
    words += leaf;
  }
  if (words != n_words || n_nodes == 0) fail("malformed: word count");
  v.idf_.resize(n_words);
  for (float& x : v.idf_) x = r.get<float>("idf");
  return v;
}

void Vocabulary::save(const std::string& path) const { io::writeFileAtomically(path, encode()); }

Vocabulary Vocabulary::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::Error(path + ": cannot open the vocabulary file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return decode(bytes, path);
}

}  // namespace amos::place
