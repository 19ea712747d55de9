#!/usr/bin/env bash
# ./rgnav spy [--lcm-url URL] — lcm-spy with every rgnav type decoded.
# Debian's /usr/bin/lcm-spy (LCM 1.3.1) passes -Xincgc, which JDK >= 9 refuses, so start the
# lcm.spy.Spy class directly. Its class path: lcm.jar, jchart2d (Debian libjchart2d-java) and
# the rgnav lcmtypes jar from the build; lcm-spy finds the rgnav classes on the class path and
# matches channels to them by fingerprint. Extra arguments go to lcm-spy.
set -euo pipefail
root=${RGNAV_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
build=${RGNAV_BUILD:-$root/build}
types_jar=$build/java/rgnav_lcmtypes.jar
if [[ ! -f $types_jar ]]; then
  echo "spy: building rgnav_lcmtypes_jar in $build" >&2
  cmake --build "$build" --target rgnav_lcmtypes_jar
fi
for jar in /usr/share/java/lcm.jar /usr/share/java/jchart2d.jar; do
  [[ -f $jar ]] || { echo "spy: $jar missing (apt-get install liblcm-java libjchart2d-java)" >&2; exit 1; }
done
if [[ -z ${DISPLAY:-} ]]; then
  echo "spy: no DISPLAY; run it on a desktop, over ssh -X, or under xvfb-run" >&2
  exit 1
fi
classpath=/usr/share/java/lcm.jar:/usr/share/java/jchart2d.jar:$types_jar
# IPv4 stack: LCM's Java udpm joins an IPv4 multicast group.
exec java -Djava.net.preferIPv4Stack=true -Xmx256m -cp "$classpath" lcm.spy.Spy "$@"
