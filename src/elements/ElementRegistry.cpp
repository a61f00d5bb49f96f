#include "strand/elements/ElementRegistry.hpp"

#include <type_traits>
#include <utility>

#include "strand/elements/ElementKinds.hpp"

namespace strand::elements {
namespace {

template <class K>
std::vector<double> referenceValuesOf(const SectionValues& v, const BodyDiscretization& d, const double* q0,
                                      int elements) {
  const typename K::Body b = K::body(v, d);
  const int n = K::referenceValueCount(b);
  std::vector<double> out(static_cast<size_t>(elements) * n);
  for (int e = 0; e < elements; ++e) K::referenceValues(b, q0 + static_cast<size_t>(e) * K::kDof, &out[static_cast<size_t>(e) * n]);
  return out;
}

template <class K>
bool velocityDependentOf(const SectionValues& v, const BodyDiscretization& d) {
  return K::velocityDependent(K::body(v, d));
}

// Kinds that provide an axial force (static double axialForce(SectionValues, BodyDiscretization,
// qElement, eta)).
template <class K, class = void>
struct HasAxialForce : std::false_type {};
template <class K>
struct HasAxialForce<K, std::void_t<decltype(K::axialForce(std::declval<const SectionValues&>(),
                                                           std::declval<const BodyDiscretization&>(),
                                                           std::declval<const double*>(), 0.0))>> : std::true_type {};

template <class K>
KindInfo infoOf() {
  static_assert(K::kBlocks <= kMaxBlocksPerElement, "raise kMaxBlocksPerElement");
  KindInfo i;
  i.name = K::kName;
  i.dim = K::kDim;
  i.blocksPerNode = K::kBlocksPerNode;
  i.layout = &K::kNodeLayout[0];
  i.orientationBlock = K::kOrientationBlock;
  i.stressFreeInitial = K::kStressFreeInitial;
  i.initialStretch = K::kInitialStretch;
  i.constantMass = K::kConstantMass;
  i.sectionKeys = &K::kSectionKeys[0];
  i.sectionKeyCount = static_cast<int>(sizeof(K::kSectionKeys) / sizeof(K::kSectionKeys[0]));
  i.options = &K::kOptions[0];
  i.optionCount = K::kOptionCount;
  i.properties = &K::properties;
  i.velocityDependent = &velocityDependentOf<K>;
  i.interpolation = &K::interpolation;
  i.interpolationAt = &K::interpolationAt;
  i.referenceValues = &referenceValuesOf<K>;
  if constexpr (HasAxialForce<K>::value) i.axialForce = &K::axialForce;
  return i;
}

const std::vector<KindInfo>& registry() {
  static const std::vector<KindInfo> kinds = [] {
    std::vector<KindInfo> out;
    forEachKind([&](auto tag) { out.push_back(infoOf<typename decltype(tag)::type>()); });
    return out;
  }();
  return kinds;
}

}  // namespace

int kindCount() { return static_cast<int>(registry().size()); }
const KindInfo& kindInfo(int kind) { return registry().at(kind); }

int findKind(const std::string& name) {
  for (int k = 0; k < kindCount(); ++k)
    if (name == registry()[k].name) return k;
  return -1;
}

std::vector<std::string> kindNames() {
  std::vector<std::string> out;
  for (const KindInfo& i : registry()) out.emplace_back(i.name);
  return out;
}

}  // namespace strand::elements
