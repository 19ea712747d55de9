// supervisor_order_t <-> OrderFields (order_auth.h): the only place that knows both.
#pragma once

#include "order_auth.h"
#include "rgnav/supervisor_order_t.hpp"

namespace rgnav::supervisor {

// OrderFields holds the message's fields under the same names: one list of them, both ways.
template <class To, class From>
To copy_order_fields(const From& f)
{
  To t;
  t.utime = f.utime;
  t.order_id = f.order_id;
  t.host = f.host;
  t.order = f.order;
  t.target = f.target;
  t.source = f.source;
  t.nonce = f.nonce;
  t.key_id = f.key_id;
  t.mac = f.mac;
  return t;
}

inline OrderFields to_order_fields(const supervisor_order_t& m) { return copy_order_fields<OrderFields>(m); }

inline supervisor_order_t to_order_msg(const OrderFields& o) { return copy_order_fields<supervisor_order_t>(o); }

}  // namespace rgnav::supervisor
