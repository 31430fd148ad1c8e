// Whether two rock.vdb files hold the same grids: every grid of the first,
// by name, in the second with the same type, active topology and values
// (index space). Transforms and file metadata (the asset's pivot, the build)
// are not compared, so bakes of builds that frame the asset differently can
// be checked for the same rock. Exit 0 when the same, 1 when not.
//   rockbake_vdb_same A.vdb B.vdb
#include <cstdio>

#include <openvdb/openvdb.h>

namespace {

template <typename GridT>
bool sameGrid(const openvdb::GridBase& a, const openvdb::GridBase& b) {
  const GridT& ga = static_cast<const GridT&>(a);
  const GridT& gb = static_cast<const GridT&>(b);
  const auto& ta = ga.tree();
  if (!ta.hasSameTopology(gb.tree()) || ta.background() != gb.tree().background()) return false;
  auto accessor = gb.getConstAccessor();
  for (auto it = ta.cbeginValueOn(); it; ++it)
    if (accessor.getValue(it.getCoord()) != *it) return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: rockbake_vdb_same A.vdb B.vdb\n");
    return 2;
  }
  openvdb::initialize();
  openvdb::io::File fa(argv[1]), fb(argv[2]);
  fa.open();
  fb.open();
  const openvdb::GridPtrVecPtr grids = fa.getGrids();
  bool same = grids->size() == fb.getGrids()->size();
  for (const auto& a : *grids) {
    const openvdb::GridBase::Ptr b = fb.hasGrid(a->getName()) ? fb.readGrid(a->getName()) : nullptr;
    bool equal = b && b->type() == a->type();
    if (equal && a->isType<openvdb::FloatGrid>())
      equal = sameGrid<openvdb::FloatGrid>(*a, *b);
    else if (equal && a->isType<openvdb::BoolGrid>())
      equal = sameGrid<openvdb::BoolGrid>(*a, *b);
    else if (equal)
      equal = false;  // a type rock.vdb does not hold
    std::printf("%s: %s\n", a->getName().c_str(), equal ? "same" : "DIFFERS");
    same &= equal;
  }
  return same ? 0 : 1;
}
