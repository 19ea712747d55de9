// supervisor_order_t <-> OrderFields (order_auth.h): the only place that knows both.
#pragma once

#include "order_auth.h"
#include "rgnav/supervisor_order_t.hpp"

namespace rgnav::supervisor {

inline OrderFields to_order_fields(const supervisor_order_t& m)
{
  OrderFields o;
  o.utime = m.utime;
  o.order_id = m.order_id;
  o.host = m.host;
  o.order = m.order;
  o.target = m.target;
  o.source = m.source;
  o.nonce = m.nonce;
  o.key_id = m.key_id;
  o.mac = m.mac;
  return o;
}

inline supervisor_order_t to_order_msg(const OrderFields& o)
{
  supervisor_order_t m;
  m.utime = o.utime;
  m.order_id = o.order_id;
  m.host = o.host;
  m.order = o.order;
  m.target = o.target;
  m.source = o.source;
  m.nonce = o.nonce;
  m.key_id = o.key_id;
  m.mac = o.mac;
  return m;
}

}  // namespace rgnav::supervisor
