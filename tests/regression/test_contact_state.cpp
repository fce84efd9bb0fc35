// The contact state (include/emcontact/contact/state.hpp) and the entries that cross ranks
// (Contact::gather) on the stack of two blocks on the ground, whose lower block's nodes are
// slaves on the ground and masters of the upper block (chains, docs/THEORY.md §3): every rank
// holds its own entries and, of the other ranks', exactly those whose slave is a master node,
// with the values every rank's entries have (Contact::gather_all); the state's Views hold the
// same entries and give them back unchanged.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <string>
#include <vector>

#include "emcontact/app/simulation.hpp"
#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/state.hpp"

namespace c = emc::contact;

namespace {

std::unique_ptr<emc::app::Simulation> stack() {
  emc::app::Options o;
  o.input = std::string(EMC_TEST_DIR) + "/stack.xml";
  o.overrides = {"Contact/top on low/type=coulomb", "Contact/top on low/friction coefficient=0.3"};
  return emc::app::setup(o, Tpetra::getDefaultComm());
}

/// One entry per slave node of mine of each pair, on its pair's first facet, with values that
/// tell entries apart (xi, slip on every other one).
std::vector<c::Active> my_entries(const c::Contact& contact) {
  std::vector<c::Active> out;
  for (std::size_t p = 0; p < contact.pairs().size(); ++p)
    for (int s : contact.nodes().my_slaves(static_cast<int>(p))) {
      c::Active a;
      a.slave = s;
      a.pair = static_cast<int>(p);
      a.facet = static_cast<int>(s % contact.pairs()[p].facets.size());
      a.xi[0] = 0.25 + 1e-3 * (s % 7);
      a.xi[1] = 0.5 - 1e-3 * (s % 5);
      a.slip = contact.pairs()[p].kind == c::Kind::coulomb && s % 2 == 0;
      a.dir[0] = a.slip ? 1.0 : 0.0;
      out.push_back(a);
    }
  std::sort(out.begin(), out.end());
  return out;
}

void expect_same(const c::Active& a, const c::Active& b, const std::string& what) {
  EXPECT_EQ(a.slave, b.slave) << what;
  EXPECT_EQ(a.pair, b.pair) << what;
  EXPECT_EQ(a.facet, b.facet) << what;
  EXPECT_EQ(a.xi[0], b.xi[0]) << what;
  EXPECT_EQ(a.xi[1], b.xi[1]) << what;
  EXPECT_EQ(a.slip, b.slip) << what;
}

}  // namespace

TEST(ContactState, OnlyChainLinksCrossRanks) {
  auto sim = stack();
  const c::Contact& contact = *sim->contact;
  const auto mine = my_entries(contact);
  const c::ActiveIndex index = contact.gather(mine), all = contact.gather_all(mine);
  std::vector<int> own;
  for (const auto& a : mine) own.push_back(a.slave);
  int links = 0, left_out = 0;
  for (const auto& [s, a] : all.by_slave) {
    const bool is_mine = std::binary_search(own.begin(), own.end(), s);
    const auto it = index.by_slave.find(s);
    if (is_mine || contact.master_node(s)) {
      ASSERT_NE(it, index.by_slave.end()) << "entry of slave " << s;
      expect_same(it->second, a, "slave " + std::to_string(s));
      links += !is_mine;
    } else {
      EXPECT_EQ(it, index.by_slave.end())
          << "another rank's entry of slave " << s << " (not a master node) crossed ranks";
      ++left_out;
    }
  }
  EXPECT_EQ(index.ghosts.size(), static_cast<std::size_t>(links));
  for (const auto& g : index.ghosts) {
    EXPECT_TRUE(contact.master_node(g.slave)) << g.slave;
    EXPECT_FALSE(std::binary_search(own.begin(), own.end(), g.slave)) << g.slave;
  }
  // the lower block's slaves are masters of the upper one: some entries are links; the upper
  // block's are not
  int any_link = 0, any_plain = 0;
  for (const auto& [s, a] : all.by_slave) (contact.master_node(s) ? any_link : any_plain) = 1;
  EXPECT_EQ(any_link, 1);
  EXPECT_EQ(any_plain, 1);
  if (Tpetra::getDefaultComm()->getSize() > 1) {  // some entries stay where they are
    int total = 0;
    Teuchos::reduceAll(*Tpetra::getDefaultComm(), Teuchos::REDUCE_SUM, 1, &left_out, &total);
    EXPECT_GT(total, 0) << "no entry was left on its rank";
  }
}

TEST(ContactState, HoldsTheEntriesAndGivesThemBack) {
  auto sim = stack();
  const c::Contact& contact = *sim->contact;
  const auto mine = my_entries(contact);
  const c::ActiveIndex index = contact.gather(mine);
  contact.select(*sim->state.u, *sim->state.u, index);
  c::ContactState st = c::make_state(contact, mine, index.ghosts);
  ASSERT_EQ(st.local, static_cast<int>(mine.size()));
  ASSERT_EQ(st.size(), static_cast<int>(mine.size() + index.ghosts.size()));
  const auto rows = c::host_entries(st, 0, st.size());
  for (std::size_t k = 0; k < mine.size(); ++k) {
    expect_same(rows[k], mine[k], "my row " + std::to_string(k));
    EXPECT_EQ(rows[k].dir[0], mine[k].dir[0]);
  }
  for (std::size_t j = 0; j < index.ghosts.size(); ++j)
    expect_same(rows[mine.size() + j], index.ghosts[j], "ghost row " + std::to_string(j));
  // the rows that slide (Coulomb in slip) per law kind
  auto sliding = Kokkos::create_mirror_view_and_copy(
      Kokkos::HostSpace(), st.sliding[static_cast<int>(c::Kind::coulomb)]);
  std::vector<int> expect;
  for (std::size_t k = 0; k < mine.size(); ++k)
    if (mine[k].slip) expect.push_back(static_cast<int>(k));
  ASSERT_EQ(sliding.extent(0), expect.size());
  for (std::size_t j = 0; j < expect.size(); ++j) EXPECT_EQ(sliding(j), expect[j]);
  // new ghosts keep my rows; my rows go back to the host list unchanged
  c::set_ghosts(st, {});
  EXPECT_EQ(st.size(), st.local);
  auto back = mine;
  for (auto& a : back) a.xi[0] = a.xi[1] = -1;
  c::to_host(st, back);
  for (std::size_t k = 0; k < mine.size(); ++k)
    expect_same(back[k], mine[k], "back " + std::to_string(k));
}
