// A runtime::Node over a FakeBus, for synchronous node tests: build the adapter under test on
// `node`; `bus` records what it publishes and delivers what the test sends. Plus decoding of
// what was published on a channel.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "bus/fake_bus.h"
#include "bus/typed.h"
#include "runtime/node.h"

namespace rgnav::testing {

struct FakeBusNode
{
  explicit FakeBusNode(runtime::NodeOptions options)
  {
    auto owned = std::make_unique<bus::FakeBus>();
    bus = owned.get();
    node = std::make_unique<runtime::Node>(std::move(options), std::move(owned));
  }
  explicit FakeBusNode(const std::string& name) : FakeBusNode(named(name)) {}

  bus::FakeBus* bus;  // owned by node
  std::unique_ptr<runtime::Node> node;

 private:
  static runtime::NodeOptions named(const std::string& name)
  {
    runtime::NodeOptions o;
    o.name = name;
    return o;
  }
};

// Every message published on `channel`, decoded; one that does not decode fails the test.
template <class T>
std::vector<T> decoded(const bus::FakeBus& bus, const std::string& channel)
{
  std::vector<T> out;
  for (const auto& p : bus.published_on(channel)) {
    T m;
    std::string why;
    EXPECT_TRUE(bus::decode(p.data.data(), p.data.size(), &m, &why)) << why;
    out.push_back(m);
  }
  return out;
}

}  // namespace rgnav::testing
