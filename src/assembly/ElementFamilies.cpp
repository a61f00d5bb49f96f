// One KernelFamily per kind of elements::AllKinds, chosen by the group's kind index: the typed
// loops of every kind are instantiated here, once.
#include <stdexcept>

#include "KernelFamily.hpp"
#include "strand/elements/ElementKinds.hpp"

namespace strand::assembly {

std::unique_ptr<ElementFamily> makeElementFamily(const model::Model& model, const model::DofMap& dofs,
                                                 const model::DofMap::LocalGroup& local,
                                                 const std::vector<double>& q0Local) {
  std::unique_ptr<ElementFamily> family;
  elements::withKind(model.groups()[local.group].kind, [&](auto tag) {
    using K = typename decltype(tag)::type;
    if (K::kDim != model.dim()) throw std::logic_error(std::string(K::kName) + " in a scene of another dimension");
    family = std::make_unique<KernelFamily<K>>(model, dofs, local, q0Local);
  });
  if (!family) throw std::logic_error("no element kind with index " + std::to_string(model.groups()[local.group].kind));
  return family;
}

}  // namespace strand::assembly
