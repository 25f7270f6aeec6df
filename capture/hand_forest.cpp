#include "capture/hand_forest.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>

#include "capture/kinect_depth.h"
#include "capture/untrusted.h"

// The trained model, embedded by hand_forest_model.S.
extern "C" const uint8_t gb_hand_forest_model_begin[];
extern "C" const uint8_t gb_hand_forest_model_end[];

namespace gb {

namespace {

constexpr char kMagic[8] = {'G', 'B', 'H', 'A', 'N', 'D', 'F', '2'};

class Writer {
 public:
  template <typename T>
  void put(const T& value) {
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void putText(const std::string& text) {
    put(static_cast<uint32_t>(text.size()));
    bytes_.insert(bytes_.end(), text.begin(), text.end());
  }
  std::vector<uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<uint8_t> bytes_;
};

class Reader {
 public:
  Reader(const uint8_t* bytes, size_t size) : p_(bytes), end_(bytes + size) {}
  template <typename T>
  T get() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, p_, sizeof(T));
    p_ += sizeof(T);
    return value;
  }
  std::string getText() {
    const uint32_t size = get<uint32_t>();
    need(size);
    std::string text(reinterpret_cast<const char*>(p_), size);
    p_ += size;
    return text;
  }
  [[nodiscard]] size_t left() const { return static_cast<size_t>(end_ - p_); }

 private:
  void need(size_t n) const {
    if (static_cast<size_t>(end_ - p_) < n) throw std::runtime_error("hand forest model: truncated");
  }
  const uint8_t* p_;
  const uint8_t* end_;
};

// A tree whose every path ends in a leaf: children inside the node list, leaves inside the leaf list, and
// children always after their parent (so no path loops).
void checkTree(const DecisionTree& tree) {
  if (tree.nodes.empty()) throw std::runtime_error("hand forest model: a tree without nodes");
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const int32_t next = tree.nodes[i].next;
    const bool inside = next >= 0 ? static_cast<size_t>(next) > i && static_cast<size_t>(next) + 1 < tree.nodes.size()
                                  : static_cast<size_t>(-(next + 1)) < tree.leaves.size();
    if (!inside) throw std::runtime_error("hand forest model: a node points outside its tree");
  }
}

}  // namespace

ClassProbabilities HandForest::classify(const BodyDepth& image, int u, int v, float z) const {
  ClassProbabilities p{};
  for (const DecisionTree& tree : trees) {
    const ClassProbabilities& leaf = tree.classify(image, u, v, z);
    for (int c = 0; c < kPixelClasses; ++c) p[c] += leaf[c];
  }
  for (float& value : p) value /= static_cast<float>(trees.size());
  return p;
}

// The file: kMagic, the payload's size (uint64), then the payload deflated (zlib). The payload: the line it was
// trained on, the push back, the trees; a tree is its node count, each node (a split: its two offsets, its
// threshold and its left child's index; a leaf: its negative leaf number only), its leaf count and each leaf's
// three probabilities in 255ths.
std::vector<uint8_t> HandForest::serialize() const {
  Writer w;
  w.putText(trainedOn);
  w.put(surfaceToCentre);
  w.put(static_cast<uint32_t>(trees.size()));
  for (const DecisionTree& tree : trees) {
    w.put(static_cast<uint32_t>(tree.nodes.size()));
    for (const ForestNode& n : tree.nodes) {
      w.put(n.next);
      if (n.next < 0) continue;
      for (const int16_t o : n.feature.a) w.put(o);
      for (const int16_t o : n.feature.b) w.put(o);
      w.put(n.threshold);
    }
    w.put(static_cast<uint32_t>(tree.leaves.size()));
    for (const ClassProbabilities& leaf : tree.leaves)
      for (const float p : leaf) w.put(static_cast<uint8_t>(std::lround(255.0f * std::clamp(p, 0.0f, 1.0f))));
  }
  const std::vector<uint8_t> payload = w.take();
  uLongf packedSize = compressBound(static_cast<uLong>(payload.size()));
  std::vector<uint8_t> packed(packedSize);
  if (compress2(packed.data(), &packedSize, payload.data(), static_cast<uLong>(payload.size()), 9) != Z_OK)
    throw std::runtime_error("hand forest model: cannot be compressed");
  Writer file;
  for (const char c : kMagic) file.put(c);
  file.put(static_cast<uint64_t>(payload.size()));
  std::vector<uint8_t> bytes = file.take();
  bytes.insert(bytes.end(), packed.begin(), packed.begin() + static_cast<long>(packedSize));
  return bytes;
}

HandForest HandForest::deserialize(const uint8_t* bytes, size_t size) {
  constexpr uint64_t kLargestPayload = uint64_t{256} << 20;  // bytes: far beyond any forest this trains
  Reader file(bytes, size);
  for (const char c : kMagic)
    if (file.get<char>() != c) throw std::runtime_error("hand forest model: not a giantbubble hand forest");
  const auto payloadSize = file.get<uint64_t>();
  if (payloadSize > kLargestPayload) throw std::runtime_error("hand forest model: larger than any forest");
  std::vector<uint8_t> payload(payloadSize);
  uLongf unpacked = static_cast<uLongf>(payloadSize);
  const size_t header = sizeof kMagic + sizeof(uint64_t);
  uLong packed = static_cast<uLong>(size - header);
  if (uncompress2(payload.data(), &unpacked, bytes + header, &packed) != Z_OK || unpacked != payloadSize)
    throw std::runtime_error("hand forest model: damaged (it does not inflate to its stated size)");
  if (packed != size - header) throw std::runtime_error("hand forest model: bytes after its compressed payload");
  Reader r(payload.data(), payload.size());
  HandForest forest;
  forest.trainedOn = r.getText();
  forest.surfaceToCentre = r.get<float>();
  if (!(std::abs(forest.surfaceToCentre) <= 1.0f))  // NaN too
    throw std::runtime_error("hand forest model: its push back to the hand's centre is not within 1 m");
  const uint32_t trees = r.get<uint32_t>();
  if (trees == 0 || trees > 64) throw std::runtime_error("hand forest model: " + std::to_string(trees) + " trees");
  for (uint32_t t = 0; t < trees; ++t) {
    DecisionTree& tree = forest.trees.emplace_back();
    const uint32_t nodes = r.get<uint32_t>();
    if (nodes > r.left() / 4) throw std::runtime_error("hand forest model: truncated");
    tree.nodes.resize(nodes);
    for (ForestNode& n : tree.nodes) {
      n.next = r.get<int32_t>();
      if (n.next < 0) continue;
      for (int16_t& o : n.feature.a) o = r.get<int16_t>();
      for (int16_t& o : n.feature.b) o = r.get<int16_t>();
      n.threshold = r.get<float>();
      // A NaN threshold sends every pixel right (every comparison with NaN is false): a model that finds nothing.
      if (!std::isfinite(n.threshold)) throw std::runtime_error("hand forest model: a threshold is not a number");
    }
    const uint32_t leaves = r.get<uint32_t>();
    if (leaves > r.left() / kPixelClasses) throw std::runtime_error("hand forest model: truncated");
    tree.leaves.resize(leaves);
    for (ClassProbabilities& leaf : tree.leaves) {
      float sum = 0.0f;
      for (float& p : leaf) sum += p = static_cast<float>(r.get<uint8_t>()) / 255.0f;
      for (float& p : leaf) p = sum > 0.0f ? p / sum : 1.0f / static_cast<float>(kPixelClasses);
    }
    checkTree(tree);
  }
  if (r.left() != 0) throw std::runtime_error("hand forest model: bytes after the last tree");
  return forest;
}

HandForest readHandForest(const std::string& path) {
  const std::string named = "hand forest model " + printablePath(path);
  std::string why, bytes;
  const InputFile file = openInputFile(path, kMaxHandForestBytes, why);
  if (!file || !readWhole(file.get(), bytes, why)) throw std::runtime_error(named + " " + why);
  try {
    return HandForest::deserialize(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(printablePath(path) + ": " + e.what());
  }
}

const HandForest& HandForest::builtin() {
  static const HandForest forest = deserialize(
      gb_hand_forest_model_begin, static_cast<size_t>(gb_hand_forest_model_end - gb_hand_forest_model_begin));
  return forest;
}

}  // namespace gb

namespace gb {

namespace {

struct ClassifiedPixel {
  Eigen::Vector3d point;
  float probability[2];  // left hand, right hand
  double area;           // m^2 of surface the pixel stands for
};

// A pixel of one hand class: its surface point and its weight, the class's probability times its area.
struct WeightedPoint {
  Eigen::Vector3d point;
  double weight;
};

// One mean-shift step from `at` with a Gaussian kernel exp(-d^2 / bandwidth^2), cut at 3 bandwidths; `density`
// gets the kernel-weighted sum.
Eigen::Vector3d shiftedMean(const std::vector<WeightedPoint>& points, const Eigen::Vector3d& at, double bandwidth,
                            double* density) {
  const double inverse = 1.0 / (bandwidth * bandwidth);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (const WeightedPoint& p : points) {
    const double d2 = (p.point - at).squaredNorm() * inverse;
    if (d2 >= 9.0) continue;
    const double w = p.weight * std::exp(-d2);
    sum += w * p.point;
    total += w;
  }
  if (density) *density = total;
  return total > 0.0 ? Eigen::Vector3d(sum / total) : at;
}

// The modes of one class's density, strongest first: mean shift from the surest points, at most kMaxClimbs
// climbs, each seed at least two bandwidths from the modes found so far; modes closer than a bandwidth are one.
std::vector<std::pair<Eigen::Vector3d, double>> densityModes(const std::vector<WeightedPoint>& points,
                                                             const std::vector<float>& probability, double bandwidth) {
  constexpr int kMaxClimbs = 8;
  std::vector<size_t> order(points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return probability[a] > probability[b]; });
  std::vector<std::pair<Eigen::Vector3d, double>> modes;
  int climbs = 0;
  for (size_t k = 0; k < order.size() && climbs < kMaxClimbs; ++k) {
    Eigen::Vector3d m = points[order[k]].point;
    bool near = false;
    for (const auto& found : modes) near = near || (found.first - m).norm() < bandwidth;
    if (near) continue;
    ++climbs;
    double density = 0.0;
    for (int step = 0; step < 15; ++step) {
      const Eigen::Vector3d next = shiftedMean(points, m, bandwidth, &density);
      const bool settled = (next - m).squaredNorm() < 4e-6;  // 2 mm
      m = next;
      if (settled) break;
    }
    bool merged = false;
    for (const auto& found : modes) merged = merged || (found.first - m).norm() < bandwidth;
    if (!merged) modes.emplace_back(m, density);
  }
  std::sort(modes.begin(), modes.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  return modes;
}

// The hand's visible front around a mode: the mode moved along its ray to the depth in front of which lies a
// small share of the hand surface within a bandwidth of its ray. A hand pointing at the camera hides its
// forearm behind it, whose pixels pull the mode back; the front is the hand's whatever way it points.
Eigen::Vector3d frontOf(const std::vector<WeightedPoint>& points, const Eigen::Vector3d& at, const ModeOptions& o) {
  const double bandwidth = o.bandwidth;
  const Eigen::Vector3d ray = at.normalized();
  std::vector<std::pair<double, double>> depths;  // along the ray, weight
  double total = 0.0;
  for (const WeightedPoint& p : points) {
    const double along = p.point.dot(ray);
    if ((p.point - along * ray).norm() > bandwidth || std::abs(along - at.norm()) > 3.0 * bandwidth) continue;
    depths.emplace_back(along, p.weight);
    total += p.weight;
  }
  if (depths.empty()) return at;
  std::sort(depths.begin(), depths.end());
  double sum = 0.0;
  for (const auto& [along, weight] : depths)
    if ((sum += weight) >= o.frontShare * total) return along * ray;
  return at;
}

// The performer's pixels that may be a hand, classified coarse to fine: every stride-th row and column first
// (a performer covers many more pixels than a hand needs), then every pixel of the blocks around the coarse
// pixels that may be a hand. Each keeps the surface area it stands for.
std::vector<ClassifiedPixel> classifyCoarseToFine(const BodyDepth& body, const HandForest& forest,
                                                  const ModeOptions& o) {
  int count = 0;
  for (const float z : body.depth) count += z > 0.0f ? 1 : 0;
  const int stride = count > o.maxPixels ? static_cast<int>(std::ceil(std::sqrt(double(count) / o.maxPixels))) : 1;
  std::vector<ClassifiedPixel> pixels;
  const auto keep = [&](int u, int v, float z, const ClassProbabilities& p, int block) {
    if (p[kLeftHandPixel] < o.minProbability && p[kRightHandPixel] < o.minProbability) return;
    const double side = static_cast<double>(block) * z / BodyDepth::kFocal;
    pixels.push_back({kinect::pixelToCamera(2.0 * (body.left + u), 2.0 * (body.top + v), z),
                      {p[kLeftHandPixel], p[kRightHandPixel]},
                      side * side});
  };
  const auto depthAt = [&](int u, int v) { return body.depth[static_cast<size_t>(v * body.width + u)]; };
  for (int v = 0; v < body.height; v += stride)
    for (int u = 0; u < body.width; u += stride) {
      const float z = depthAt(u, v);
      if (z <= 0.0f) continue;
      const ClassProbabilities p = forest.classify(body, body.left + u, body.top + v, z);
      const bool handLike = p[kLeftHandPixel] >= o.refineProbability || p[kRightHandPixel] >= o.refineProbability;
      if (stride == 1 || !handLike) {
        keep(u, v, z, p, stride);
        continue;
      }
      for (int dv = 0; dv < stride && v + dv < body.height; ++dv)
        for (int du = 0; du < stride && u + du < body.width; ++du) {
          const float zz = depthAt(u + du, v + dv);
          if (zz <= 0.0f) continue;
          keep(u + du, v + dv, zz,
               du == 0 && dv == 0 ? p : forest.classify(body, body.left + u + du, body.top + v + dv, zz), 1);
        }
    }
  return pixels;
}

}  // namespace

std::array<std::vector<HandMode>, 2> findHandModes(const BodyDepth& body, const HandForest& forest,
                                                   const ModeOptions& o) {
  const std::vector<ClassifiedPixel> pixels = classifyCoarseToFine(body, forest, o);
  std::vector<WeightedPoint> points[2];
  std::vector<float> probability[2];
  for (const ClassifiedPixel& p : pixels)
    for (int hand = 0; hand < 2; ++hand)
      if (p.probability[hand] >= o.minProbability) {
        points[hand].push_back({p.point, p.probability[hand] * p.area});
        probability[hand].push_back(p.probability[hand]);
      }
  std::array<std::vector<HandMode>, 2> modes;
  for (int hand = 0; hand < 2; ++hand)
    for (const auto& [at, density] : densityModes(points[hand], probability[hand], o.bandwidth)) {
      double other = 0.0;
      shiftedMean(points[1 - hand], at, o.bandwidth, &other);
      const Eigen::Vector3d centre = frontOf(points[hand], at, o) + forest.surfaceToCentre * at.normalized();
      HandMode mode;
      mode.position = {centre.x(), centre.y(), centre.z()};
      mode.weight = density;
      mode.share = density / (density + other);
      modes[static_cast<size_t>(hand)].push_back(mode);
    }
  return modes;
}

}  // namespace gb
