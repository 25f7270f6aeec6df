#pragma once
// Which of the performer's depth pixels are a hand: a randomized decision forest over depth-comparison
// features, after Shotton, Fitzgibbon, Cook, Sharp, Finocchio, Moore, Kipman and Blake, "Real-time human pose
// recognition in parts from single depth images" (CVPR 2011), the method behind the Kinect SDK's skeleton.
//
// Each pixel x of the performer (depth d(x)) is classified by comparing the depth at two offsets from it,
//   f(x) = D(x + a / d(x)) - D(x + b / d(x)),
// where the offsets a and b are metres at the pixel's depth (so a feature looks at the same part of a body
// whatever its distance from the camera), D is the performer's depth and kBackground anywhere else (or outside
// the image), and b may be 0 (then D(x) = d(x)). Each split node sends a pixel left when f(x) < its threshold;
// each leaf holds the probabilities of the classes. The forest's probability is the mean of its trees'.
//
// The classes are the performer's own left hand, right hand and the rest of the body, in the unmirrored view
// (the performer's left hand on the image's right). The forest is trained on real Kinect v1 depth with the
// Kinect SDK skeleton tracker's hands as labels (hand_forest_training.h, gb_train_hand_forest) and is
// compiled into the program (HandForest::builtin()).

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace gb {

// The performer's depth on the detector's half-resolution grid: 0 where a pixel is not the performer's.
struct BodyDepth {
  static constexpr int kWidth = 320, kHeight = 240;
  static constexpr float kBackground = 10.0f;  // m: D of every pixel that is not the performer's
  // Focal length of the half-resolution grid (pixels): an offset of o metres at depth d is o * kFocal / d pixels.
  static constexpr double kFocal = 594.214 / 2.0;
  int left = 0, top = 0, width = kWidth, height = kHeight;  // the window the depth is kept for (a crop when training)
  std::vector<float> depth = std::vector<float>(static_cast<size_t>(kWidth) * kHeight, 0.0f);  // row-major, window

  // D at grid pixel (u, v): the depth there, kBackground off the performer or the window.
  [[nodiscard]] float at(int u, int v) const {
    const int x = u - left, y = v - top;
    if (x < 0 || y < 0 || x >= width || y >= height) return kBackground;
    const float z = depth[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
    return z > 0.0f ? z : kBackground;
  }
};

enum PixelClass : int { kBodyPixel = 0, kLeftHandPixel = 1, kRightHandPixel = 2, kPixelClasses = 3 };

using ClassProbabilities = std::array<float, kPixelClasses>;

// A depth-comparison feature: offsets in millimetres at the pixel's depth (grid x to the right, y down).
struct DepthFeature {
  std::array<int16_t, 2> a{}, b{};
};

// The feature's value at grid pixel (u, v) of depth z (the pixel's own, > 0).
inline float featureValue(const BodyDepth& image, int u, int v, float z, const DepthFeature& f) {
  const float scale = static_cast<float>(BodyDepth::kFocal * 1e-3) / z;  // pixels per millimetre of offset
  // Rounded to the nearest pixel; offsets stay far inside +-1024 pixels (0.6 m at 0.5 m is 360).
  const auto nearest = [](float x) { return static_cast<int>(x + 1024.5f) - 1024; };
  const auto offset = [&](const std::array<int16_t, 2>& o) {
    if (o[0] == 0 && o[1] == 0) return z;
    return image.at(u + nearest(scale * o[0]), v + nearest(scale * o[1]));
  };
  return offset(f.a) - offset(f.b);
}

struct ForestNode {
  DepthFeature feature;
  float threshold = 0.0f;
  int32_t next = 0;  // >= 0: the left child's index (the right child follows it); < 0: leaf number -next - 1
};

struct DecisionTree {
  std::vector<ForestNode> nodes;  // nodes[0] is the root
  std::vector<ClassProbabilities> leaves;

  [[nodiscard]] const ClassProbabilities& classify(const BodyDepth& image, int u, int v, float z) const {
    int32_t i = 0;
    while (nodes[static_cast<size_t>(i)].next >= 0) {
      const ForestNode& n = nodes[static_cast<size_t>(i)];
      i = n.next + (featureValue(image, u, v, z, n.feature) < n.threshold ? 0 : 1);
    }
    return leaves[static_cast<size_t>(-nodes[static_cast<size_t>(i)].next - 1)];
  }
};

struct HandForest {
  std::vector<DecisionTree> trees;
  // m: how far a hand's centre (the skeleton's hand joint) lies behind the middle of its visible surface,
  // measured on the training data.
  float surfaceToCentre = 0.0f;
  std::string trainedOn;  // one line: the data and the settings it was trained with

  // Class probabilities of grid pixel (u, v) of the performer, whose depth there is z.
  [[nodiscard]] ClassProbabilities classify(const BodyDepth& image, int u, int v, float z) const;

  // The model as bytes and back (little-endian; deserialize throws std::runtime_error on a malformed model).
  [[nodiscard]] std::vector<uint8_t> serialize() const;
  static HandForest deserialize(const uint8_t* bytes, size_t size);
  // The forest compiled into the program (capture/models/hand_forest.bin).
  static const HandForest& builtin();
};

// The largest model file read: the built-in forest is 2.1 MB.
inline constexpr std::uintmax_t kMaxHandForestBytes = std::uintmax_t{64} << 20;

// A model file written by gb_train_hand_forest; throws std::runtime_error naming the file and the problem (a FIFO, a
// device or a folder is named as such, not read; a file over kMaxHandForestBytes is refused unread).
HandForest readHandForest(const std::string& path);

// A hand found by the forest: a mode of the density of its class's pixels over the performer's surface.
struct HandMode {
  std::array<double, 3> position{};  // camera space (m): the mode pushed back to the hand's centre
  double weight = 0.0;               // m^2: the class's probability summed over the surface near the mode
  double share = 0.0;                // 0..1: of the hand probability near the mode, the share of this class
};

struct ModeOptions {
  double bandwidth = 0.06;         // m: Gaussian kernel of the mean shift
  float minProbability = 0.1f;     // pixels less sure than this take no part
  float refineProbability = 0.3f;  // coarse pixels this sure have their neighbours classified too
  double frontShare = 0.1;         // the hand's front: the depth with this share of its surface in front
  int maxPixels = 2500;            // the performer's pixels classified per frame at most (a near body is subsampled)
};

// The modes of each hand class (kLeftHandPixel, kRightHandPixel), strongest first, over the performer's pixels.
std::array<std::vector<HandMode>, 2> findHandModes(const BodyDepth& body, const HandForest& forest,
                                                   const ModeOptions& options = {});

}  // namespace gb
