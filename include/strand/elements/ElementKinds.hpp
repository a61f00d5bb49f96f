// The element kinds Strand knows, as one compile-time list. Everything else is derived from it:
// the registry's names, dimensions, node layouts and section keys (ElementRegistry.hpp: the scene
// reader, the model, the output), and the assembler's typed loop per kind (KernelFamily<K>).
// Adding a kind: docs/architecture.md, "Element kinds", the checklist.
#pragma once
#include <utility>

#include "strand/elements/AleBeamShaft.hpp"
#include "strand/elements/AleCable.hpp"
#include "strand/elements/AncfBeam2d.hpp"
#include "strand/elements/AncfCable.hpp"

namespace strand::elements {

template <class... K>
struct KindList {
  static constexpr int size = sizeof...(K);
};

// The registry order is the kind index (model::Body::kind).
using AllKinds = KindList<AncfCable2d, AncfCable3d, AncfBeam2dShear, AncfBeam2dLinear, AleCable2d, AleCable3d,
                          AleBeamShaft3d>;

template <class K>
struct KindTag {
  using type = K;
};

// f(KindTag<K>{}) for the kind-th type of the list: a fold over the list, so that no code names
// the kinds one by one.
template <class F, class... K>
void withKindIn(KindList<K...>, int kind, F&& f) {
  int i = 0;
  (void)((i++ == kind ? (f(KindTag<K>{}), true) : false) || ...);
}

template <class F>
void withKind(int kind, F&& f) {
  withKindIn(AllKinds{}, kind, std::forward<F>(f));
}

// f(KindTag<K>{}) for every kind, in registry order.
template <class F, class... K>
void forEachKindIn(KindList<K...>, F&& f) {
  (f(KindTag<K>{}), ...);
}

template <class F>
void forEachKind(F&& f) {
  forEachKindIn(AllKinds{}, std::forward<F>(f));
}

}  // namespace strand::elements
