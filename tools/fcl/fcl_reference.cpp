#include "tools/fcl/fcl_reference.hpp"

#include "collision/contacts.hpp"
#include "geometry/clock.hpp"
#include "geometry/organ_mesh.hpp"
#include "tools/bench_timing.hpp"

#include <fcl/fcl.h>

#include <algorithm>
#include <chrono>
#include <memory>

namespace canopy {
namespace {

struct Search {
  const Stand* stand;
  std::vector<std::pair<int, int>> pairs;
};

bool on_pair(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  auto* s = static_cast<Search*>(data);
  int a = static_cast<int>(reinterpret_cast<std::intptr_t>(o1->getUserData()));
  int b = static_cast<int>(reinterpret_cast<std::intptr_t>(o2->getUserData()));
  if (a > b) std::swap(a, b);
  const auto& ra = s->stand->organs[static_cast<std::size_t>(a)];
  const auto& rb = s->stand->organs[static_cast<std::size_t>(b)];
  if (adjacent(ra, a, rb, b)) return false;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(o1, o2, request, result);
  if (result.isCollision()) s->pairs.emplace_back(a, b);
  return false;  // keep going
}

}  // namespace

struct FclScene::Impl {
  const Stand* stand = nullptr;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  mutable fcl::DynamicAABBTreeCollisionManagerd manager;
  double build_s = 0;
};

FclScene::FclScene(const Stand& stand, PrototypeLibrary& lib, const KindMask& collide)
    : impl_(std::make_unique<Impl>()) {
  using Model = fcl::BVHModel<fcl::OBBRSSd>;
  const auto t = std::chrono::steady_clock::now();
  impl_->stand = &stand;
  std::vector<fcl::CollisionObjectd*> raw;
  OrganMesh mesh;
  for (std::size_t id = 0; id < stand.organ_count(); ++id) {
    const OrganRecord& r = stand.organs[id];
    if (!collide[static_cast<std::size_t>(r.kind)]) continue;
    organ_mesh(stand, id, lib, mesh, true);
    const Vec3d off = stand.offset(static_cast<std::size_t>(r.plant));
    std::vector<fcl::Vector3d> v;
    for (const Vec3f& p : mesh.positions) v.emplace_back(off.x + p.x, off.y + p.y, p.z);
    std::vector<fcl::Triangle> tris;
    const auto& idx = mesh.prototype->indices;
    for (std::size_t i = 0; i < idx.size(); i += 3) tris.emplace_back(idx[i], idx[i + 1], idx[i + 2]);
    auto model = std::make_shared<Model>();
    model->beginModel();
    model->addSubModel(v, tris);
    model->endModel();
    impl_->objects.push_back(std::make_unique<fcl::CollisionObjectd>(model, fcl::Transform3d::Identity()));
    impl_->objects.back()->setUserData(reinterpret_cast<void*>(static_cast<std::intptr_t>(id)));
    raw.push_back(impl_->objects.back().get());
  }
  impl_->manager.registerObjects(raw);
  impl_->manager.setup();
  impl_->build_s = seconds_since(t);
}

FclScene::~FclScene() = default;

double FclScene::build_s() const { return impl_->build_s; }

std::vector<std::pair<int, int>> FclScene::query() const {
  Search search{impl_->stand, {}};
  impl_->manager.collide(&search, on_pair);
  std::sort(search.pairs.begin(), search.pairs.end());
  return std::move(search.pairs);
}

}  // namespace canopy
