#pragma once
// A vocabulary of binary visual words for ORB descriptors, for place recognition that survives viewpoint change
// (the bag-of-binary-words approach of Galvez-Lopez and Tardos, "Bags of Binary Words for Fast Place Recognition
// in Image Sequences", T-RO 2012, which ORB-SLAM2's relocalisation and loop detection stand on).
//
// The words are the leaves of a tree built offline by hierarchical clustering of training descriptors: each node's
// descriptors are split into `branching` clusters by k-majority (k-means with k-means++ seeding, Hamming distance,
// and the bitwise majority of a cluster as its centre), down to `depth` levels. A descriptor's word is found by
// descending from the root to the nearest child at each level (branching x depth Hamming distances). Each word has
// an inverse document frequency idf = log(N / n_w) over the N training images (n_w of which contain it), so words
// seen everywhere count little. An image's bag-of-words vector holds tf-idf weights, L1-normalised.
//
// File (`amos-slam vocab` writes it; little-endian): magic "AMOSVOC\0", format version u32, branching u32, depth
// u32, node count u32, word count u32, CRC-32 of the rest u32; then per node (root first, children of a node
// contiguous): descriptor (32 bytes), first child u32, child count u32, word id u32 (0xFFFFFFFF: inner node);
// then per word its idf (f32).
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace amos::place {

using WordId = std::uint32_t;

// Sparse tf-idf vector: (word, weight) sorted by word, weights summing to 1.
struct BowVector {
  std::vector<std::pair<WordId, float>> words;
  bool empty() const { return words.empty(); }
};

// Similarity of two L1-normalised vectors: 1 - |a - b|_1 / 2, in [0, 1] (DBoW2's L1 score).
double similarity(const BowVector& a, const BowVector& b);

struct VocabularyOptions {
  int branching = 10;   // k: children per node
  int depth = 4;        // L: levels below the root (up to k^L words)
  int iterations = 15;  // k-majority iterations per node at most
  std::uint32_t seed = 1;
  void check() const;
};

class Vocabulary {
 public:
  Vocabulary() = default;

  // Clusters the descriptors of the training images (one CV_8U N x 32 matrix per image) into a tree and weights
  // its words over those images. Deterministic for a given seed.
  static Vocabulary train(const std::vector<cv::Mat>& images, const VocabularyOptions& options);

  std::string encode() const;
  // `source` names the bytes in errors (the file). Throws core::Error: not a vocabulary, version, truncated,
  // corrupt (checksum), inconsistent.
  static Vocabulary decode(const std::string& bytes, const std::string& source);
  void save(const std::string& path) const;  // atomically
  static Vocabulary load(const std::string& path);

  bool empty() const { return nodes_.empty(); }
  std::size_t numWords() const { return idf_.size(); }
  int branching() const { return branching_; }
  int depth() const { return depth_; }

  WordId word(const std::uint8_t* descriptor) const;
  // The bag-of-words vector of an image's descriptors (N x 32 CV_8U).
  BowVector transform(const cv::Mat& descriptors) const;
  float idf(WordId w) const { return idf_[w]; }

 private:
  struct Node {
    std::array<std::uint8_t, 32> descriptor{};
    std::uint32_t first_child = 0, num_children = 0;
    WordId word = kNoWord;
  };
  static constexpr WordId kNoWord = 0xFFFFFFFFu;

  std::vector<Node> nodes_;
  std::vector<float> idf_;
  int branching_ = 0, depth_ = 0;
};

}  // namespace amos::place
