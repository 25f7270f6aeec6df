#include "capture/hand_forest_training.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "capture/kinect_depth.h"

namespace gb {

namespace {

// The performer's depth cut down to the rectangle it covers (the rest of the grid reads as background anyway).
BodyDepth cropped(const BodyDepth& body) {
  int left = BodyDepth::kWidth, top = BodyDepth::kHeight, right = -1, bottom = -1;
  for (int v = 0; v < body.height; ++v)
    for (int u = 0; u < body.width; ++u)
      if (body.depth[static_cast<size_t>(v * body.width + u)] > 0.0f)
        left = std::min(left, u), right = std::max(right, u), top = std::min(top, v), bottom = std::max(bottom, v);
  BodyDepth crop;
  if (right < 0) {
    crop.width = crop.height = 0;
    crop.depth.clear();
    return crop;
  }
  crop.left = body.left + left;
  crop.top = body.top + top;
  crop.width = right - left + 1;
  crop.height = bottom - top + 1;
  crop.depth.assign(static_cast<size_t>(crop.width * crop.height), 0.0f);
  for (int v = 0; v < crop.height; ++v)
    for (int u = 0; u < crop.width; ++u)
      crop.depth[static_cast<size_t>(v * crop.width + u)] =
          body.depth[static_cast<size_t>((v + top) * body.width + u + left)];
  return crop;
}

// The same image seen in a mirror: flipped left to right about its own window.
BodyDepth mirroredImage(const BodyDepth& image) {
  BodyDepth m = image;
  for (int v = 0; v < image.height; ++v)
    std::reverse(m.depth.begin() + v * image.width, m.depth.begin() + (v + 1) * image.width);
  return m;
}

// Adds one image's pixels: every hand pixel, and up to bodyPixels body pixels at random, weighted so that the
// sampled pixels of a class stand for all of that class's pixels in the image.
void addPixels(const BodyDepth& image, const std::optional<Vec3d> (&hands)[2], bool mirrored,
               const ForestTrainingOptions& o, std::mt19937& random, ForestTrainingSet& set) {
  const auto index = static_cast<uint32_t>(set.images.size());
  std::vector<TrainingPixel> byClass[kPixelClasses];
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float z = image.depth[static_cast<size_t>(y * image.width + x)];
      if (z <= 0.0f) continue;
      // The pixel where the camera saw this point: mirrored images are mirrored back for the labels.
      const int u = image.left + (mirrored ? image.width - 1 - x : x), v = image.top + y;
      const Vec3d p = gridPoint(u, v, z);
      int label = kBodyPixel;
      double nearest = o.handRadius;
      for (int h = 0; h < 2; ++h)
        if (hands[h] && (p - *hands[h]).norm() < nearest) {
          nearest = (p - *hands[h]).norm();
          // Mirrored, the performer's left hand becomes a right hand.
          label = (h == 0) != mirrored ? kLeftHandPixel : kRightHandPixel;
        }
      TrainingPixel px;
      px.image = index;
      px.u = static_cast<int16_t>(image.left + x);
      px.v = static_cast<int16_t>(v);
      px.z = z;
      px.label = static_cast<uint8_t>(label);
      byClass[label].push_back(px);
    }
  for (int c = 0; c < kPixelClasses; ++c) {
    std::vector<TrainingPixel>& pixels = byClass[c];
    const size_t all = pixels.size(),
                 most = static_cast<size_t>(c == kBodyPixel ? o.bodyPixelsPerFrame : o.handPixelsPerFrame);
    if (all > most) {
      std::shuffle(pixels.begin(), pixels.end(), random);
      pixels.resize(most);
    }
    for (TrainingPixel& px : pixels)
      px.weight = static_cast<float>(all) / static_cast<float>(std::max<size_t>(1, pixels.size()));
    set.pixels.insert(set.pixels.end(), pixels.begin(), pixels.end());
  }
  set.images.push_back(image);
}

double entropy(const std::array<double, kPixelClasses>& counts) {
  const double total = counts[0] + counts[1] + counts[2];
  if (total <= 0.0) return 0.0;
  double h = 0.0;
  for (const double c : counts)
    if (c > 0.0) h -= c / total * std::log2(c / total);
  return h;
}

class TreeGrower {
 public:
  TreeGrower(const ForestTrainingSet& set, const ForestTrainingOptions& o, unsigned seed)
      : set_(set), o_(o), random_(seed) {}

  DecisionTree grow(std::vector<uint32_t> pixels) {
    // In image order (as the training set holds them), so that the features read one image after another from
    // the cache; a node's pixels stay in that order through every split (stable_partition).
    tree_.nodes.emplace_back();
    split(0, pixels.data(), pixels.data() + pixels.size(), 0);
    return std::move(tree_);
  }

 private:
  const ForestTrainingSet& set_;
  const ForestTrainingOptions& o_;
  std::mt19937 random_;
  DecisionTree tree_;

  float valueOf(uint32_t pixel, const DepthFeature& f) const {
    const TrainingPixel& p = set_.pixels[pixel];
    return featureValue(set_.images[p.image], p.u, p.v, p.z, f);
  }

  DepthFeature randomFeature() {
    const auto limit = static_cast<int>(std::lround(1000.0 * o_.maxOffset));
    std::uniform_int_distribution<int> offset(-limit, limit);
    DepthFeature f;
    for (int16_t& c : f.a) c = static_cast<int16_t>(offset(random_));
    // Half the features compare a point with the pixel itself, half two points around it.
    if (random_() % 2)
      for (int16_t& c : f.b) c = static_cast<int16_t>(offset(random_));
    return f;
  }

  void makeLeaf(int32_t node, const uint32_t* begin, const uint32_t* end) {
    ClassProbabilities p{};
    double total = 0.0;
    for (const uint32_t* i = begin; i != end; ++i) {
      const TrainingPixel& px = set_.pixels[*i];
      p[px.label] += px.weight;
      total += px.weight;
    }
    for (float& value : p) value = total > 0.0 ? static_cast<float>(value / total) : 0.0f;
    tree_.nodes[static_cast<size_t>(node)].next = -static_cast<int32_t>(tree_.leaves.size()) - 1;
    tree_.leaves.push_back(p);
  }

  struct Candidate {
    double gain = 0.0;
    DepthFeature feature;
    float threshold = 0.0f;
  };

  // The best threshold of one feature over the pixels that choose the split.
  Candidate bestThreshold(const DepthFeature& f, const std::vector<const TrainingPixel*>& pixels, unsigned seed) const {
    const size_t n = pixels.size();
    std::vector<float> values(n);
    for (size_t i = 0; i < n; ++i)
      values[i] = featureValue(set_.images[pixels[i]->image], pixels[i]->u, pixels[i]->v, pixels[i]->z, f);
    std::minstd_rand random(seed);
    std::vector<float> thresholds(static_cast<size_t>(o_.thresholdsPerFeature));
    for (float& t : thresholds) t = values[random() % n];
    std::sort(thresholds.begin(), thresholds.end());
    // bins[k]: pixels with exactly k thresholds at or below their value, by class.
    std::vector<std::array<double, kPixelClasses>> bins(thresholds.size() + 1, {0.0, 0.0, 0.0});
    std::array<double, kPixelClasses> all{0.0, 0.0, 0.0};
    for (size_t i = 0; i < n; ++i) {
      const auto k =
          static_cast<size_t>(std::upper_bound(thresholds.begin(), thresholds.end(), values[i]) - thresholds.begin());
      bins[k][pixels[i]->label] += 1.0;
      all[pixels[i]->label] += 1.0;
    }
    const double parent = entropy(all);
    Candidate best;
    best.feature = f;
    std::array<double, kPixelClasses> left{0.0, 0.0, 0.0};
    for (size_t t = 0; t < thresholds.size(); ++t) {
      for (int c = 0; c < kPixelClasses; ++c) left[c] += bins[t][c];  // values below thresholds[t]
      std::array<double, kPixelClasses> right{};
      for (int c = 0; c < kPixelClasses; ++c) right[c] = all[c] - left[c];
      const double nl = left[0] + left[1] + left[2], nr = right[0] + right[1] + right[2];
      if (nl < o_.minLeafPixels || nr < o_.minLeafPixels) continue;
      const double gain = parent - (nl * entropy(left) + nr * entropy(right)) / static_cast<double>(n);
      if (gain > best.gain) best.gain = gain, best.threshold = thresholds[t];
    }
    return best;
  }

  void split(int32_t node, uint32_t* begin, uint32_t* end, int depth) {
    const auto n = static_cast<size_t>(end - begin);
    int classes = 0;
    {
      bool present[kPixelClasses] = {false, false, false};
      for (const uint32_t* i = begin; i != end; ++i) present[set_.pixels[*i].label] = true;
      for (const bool p : present) classes += p ? 1 : 0;
    }
    if (depth >= o_.maxDepth || n < 2 * static_cast<size_t>(o_.minLeafPixels) || classes < 2) {
      makeLeaf(node, begin, end);
      return;
    }
    // A large node chooses its split on every stride-th pixel: a sample spread over all its images.
    const size_t stride = (n + static_cast<size_t>(o_.pixelsPerSplit) - 1) / static_cast<size_t>(o_.pixelsPerSplit);
    std::vector<DepthFeature> features(static_cast<size_t>(o_.featuresPerNode));
    std::vector<unsigned> seeds(features.size());
    for (size_t k = 0; k < features.size(); ++k)
      features[k] = randomFeature(), seeds[k] = static_cast<unsigned>(random_());
    std::vector<const TrainingPixel*> chooser;
    for (const uint32_t* i = begin; i < end; i += stride) chooser.push_back(&set_.pixels[*i]);
    std::vector<Candidate> candidates(features.size());
#pragma omp parallel for schedule(dynamic, 8) if (n > 4000)
    for (size_t k = 0; k < features.size(); ++k) candidates[k] = bestThreshold(features[k], chooser, seeds[k]);
    const Candidate best = *std::max_element(candidates.begin(), candidates.end(),
                                             [](const Candidate& a, const Candidate& b) { return a.gain < b.gain; });
    if (best.gain <= 0.0) {
      makeLeaf(node, begin, end);
      return;
    }
    uint32_t* middle = std::stable_partition(
        begin, end, [&](uint32_t pixel) { return valueOf(pixel, best.feature) < best.threshold; });
    if (middle == begin || middle == end) {
      makeLeaf(node, begin, end);
      return;
    }
    const auto children = static_cast<int32_t>(tree_.nodes.size());
    tree_.nodes[static_cast<size_t>(node)].feature = best.feature;
    tree_.nodes[static_cast<size_t>(node)].threshold = best.threshold;
    tree_.nodes[static_cast<size_t>(node)].next = children;
    tree_.nodes.emplace_back();
    tree_.nodes.emplace_back();
    split(children, begin, middle, depth + 1);
    split(children + 1, middle, end, depth + 1);
  }
};

// How far the true hands lie behind the hands the forest finds (their front, before the push back), median over
// the calibration frames: each true hand against the nearest hand of its side within 20 cm.
double medianDepthBehind(HandForest forest, const ForestTrainingSet& set) {
  constexpr double kMatch = 0.2;  // m
  forest.surfaceToCentre = 0.0f;
  std::vector<double> behind;
#pragma omp parallel for schedule(dynamic, 16)
  for (size_t k = 0; k < set.calibration.size(); ++k) {
    const CalibrationFrame& frame = set.calibration[k];
    const auto modes = findHandModes(set.images[frame.image], forest);
    for (int h = 0; h < 2; ++h) {
      if (!frame.hands[h]) continue;
      const Vec3d* nearest = nullptr;
      double distance = kMatch;
      Vec3d found;
      for (const HandMode& m : modes[static_cast<size_t>(h)]) {
        const Vec3d p(m.position[0], m.position[1], m.position[2]);
        if ((p - *frame.hands[h]).norm() < distance)
          distance = (p - *frame.hands[h]).norm(), found = p, nearest = &found;
      }
      if (!nearest) continue;
#pragma omp critical
      behind.push_back(frame.hands[h]->norm() - nearest->norm());
    }
  }
  if (behind.empty()) return 0.0;
  std::nth_element(behind.begin(), behind.begin() + static_cast<long>(behind.size() / 2), behind.end());
  return behind[behind.size() / 2];
}

}  // namespace

Vec3d gridPoint(int u, int v, double z) { return kinect::pixelToCamera(2.0 * u, 2.0 * v, z); }

// The performer seen from elsewhere: moved along the camera's axis by `shift` (m) and seen by a camera tilted
// down by `pitch` degrees, each grid pixel drawn as large as it now appears (nearer points in front).
BodyDepth reseen(const BodyDepth& body, double shift, double pitch, std::optional<Vec3d> (&hands)[2]) {
  const double a = pitch * std::numbers::pi / 180.0, c = std::cos(a), s = std::sin(a);
  const auto move = [&](const Vec3d& p) {
    const Vec3d q = p + Vec3d(0.0, 0.0, shift);
    return Vec3d(q.x(), c * q.y() + s * q.z(), -s * q.y() + c * q.z());
  };
  for (auto& hand : hands)
    if (hand) hand = move(*hand);
  BodyDepth out;
  for (int v = 0; v < body.height; ++v)
    for (int u = 0; u < body.width; ++u) {
      const float z = body.depth[static_cast<size_t>(v * body.width + u)];
      if (z <= 0.0f) continue;
      const Vec3d p = move(gridPoint(body.left + u, body.top + v, z));
      if (p.z() < 0.5) continue;
      const Eigen::Vector2d px = kinect::cameraToPixel(p) / 2.0;
      const int size = std::max(1, static_cast<int>(std::ceil(z / p.z())));
      const int u0 = static_cast<int>(std::floor(px.x())), v0 = static_cast<int>(std::floor(px.y()));
      for (int y = std::max(0, v0); y < std::min(BodyDepth::kHeight, v0 + size); ++y)
        for (int x = std::max(0, u0); x < std::min(BodyDepth::kWidth, u0 + size); ++x) {
          float& d = out.depth[static_cast<size_t>(y * BodyDepth::kWidth + x)];
          if (d == 0.0f || p.z() < d) d = static_cast<float>(p.z());
        }
    }
  return out;
}

// Adds one view of a frame: its calibration entry and its pixels, as seen and mirrored.
void addView(const BodyDepth& body, const std::optional<Vec3d> (&hands)[2], const ForestTrainingOptions& o,
             std::mt19937& random, ForestTrainingSet& set) {
  const BodyDepth image = cropped(body);
  if (image.width == 0) return;
  set.calibration.push_back({static_cast<uint32_t>(set.images.size()), {hands[0], hands[1]}});
  addPixels(image, hands, false, o, random, set);
  if (o.mirrored) addPixels(mirroredImage(image), hands, true, o, random, set);
}

void addTrainingFrame(const BodyDepth& body, const std::optional<Vec3d> (&hands)[2], const ForestTrainingOptions& o,
                      std::mt19937& random, ForestTrainingSet& set) {
  addView(body, hands, o, random, set);
  std::vector<double> depths;
  for (const float z : body.depth)
    if (z > 0.0f) depths.push_back(z);
  if (depths.empty()) return;
  std::nth_element(depths.begin(), depths.begin() + static_cast<long>(depths.size() / 2), depths.end());
  std::uniform_real_distribution<double> distance(o.nearest, o.farthest), pitch(0.0, o.maxPitch);
  for (int k = 0; k < o.otherViews; ++k) {
    std::optional<Vec3d> moved[2] = {hands[0], hands[1]};
    const BodyDepth view = reseen(body, distance(random) - depths[depths.size() / 2], pitch(random), moved);
    addView(view, moved, o, random, set);
  }
}

HandForest trainHandForest(const ForestTrainingSet& set, const ForestTrainingOptions& o) {
  HandForest forest;
  std::mt19937 random(o.seed);
  for (int t = 0; t < o.trees; ++t) {
    std::vector<uint32_t> pixels;
    std::bernoulli_distribution take(o.pixelsPerTree);
    for (uint32_t i = 0; i < set.pixels.size(); ++i)
      if (take(random)) pixels.push_back(i);
    forest.trees.push_back(TreeGrower(set, o, static_cast<unsigned>(random())).grow(std::move(pixels)));
  }
  forest.surfaceToCentre = static_cast<float>(medianDepthBehind(forest, set));
  return forest;
}

}  // namespace gb
