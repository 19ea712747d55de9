#!/usr/bin/env python3
"""How long each process's work stood still in a recorded LCM log: from every HEARTBEAT
(heartbeat_t, decoded by hand: no LCM Python bindings on the robot's Debian), the stretches in
which a process reported itself busy (busy_ms > 0) while its progress counter did not move. The
supervisor bounds exactly these stretches (work_timeout_ms in the launch configs): this says how
much of a bound a loaded run used.

  deploy/bench/heartbeat_progress.py logs/demo-<stamp>/lcm/rgnav.lcmlog

Prints per process: stretches over 500 ms and over 1000 ms, and the four longest (ms held still,
busy_ms then)."""
import collections
import struct
import sys

SYNC = 0xEDA1DA01


def events(path):
    with open(path, 'rb') as f:
        data = f.read()
    i = 0
    while i + 28 <= len(data):
        sync, _num, _utime, channel_len, data_len = struct.unpack_from('>IqqII', data, i)
        if sync != SYNC:
            i += 1  # damaged: look for the next event
            continue
        channel = data[i + 28:i + 28 + channel_len].decode(errors='replace')
        yield channel, data[i + 28 + channel_len:i + 28 + channel_len + data_len]
        i += 28 + channel_len + data_len


def lcm_string(d, o):
    n = struct.unpack_from('>i', d, o)[0]
    return d[o + 4:o + 4 + n - 1].decode(errors='replace'), o + 4 + n


def heartbeat(d):
    """name, pid, utime, progress, busy_ms of an encoded heartbeat_t (after its fingerprint)."""
    o = 8
    utime = struct.unpack_from('>q', d, o)[0]
    name, o = lcm_string(d, o + 8)
    _host, o = lcm_string(d, o)
    pid, _seq = struct.unpack_from('>iq', d, o)
    o += 12 + 1 + 36   # pid, seq; state; last_input_age_us, cpu_percent, rss_kb, messages_in, messages_dropped
    _status, o = lcm_string(d, o)
    progress, busy_ms = struct.unpack_from('>qi', d, o)
    return name, pid, utime, progress, busy_ms


def main():
    since = {}   # name -> (pid, progress, utime it last moved)
    held = collections.defaultdict(list)
    for channel, d in events(sys.argv[1]):
        if channel != 'HEARTBEAT':
            continue
        try:
            name, pid, utime, progress, busy_ms = heartbeat(d)
        except struct.error:
            continue
        last = since.get(name)
        if last and last[0] == pid and last[1] == progress:
            if busy_ms > 0:
                held[name].append(((utime - last[2]) / 1e3, busy_ms))
        else:
            since[name] = (pid, progress, utime)
    for name, stretches in sorted(held.items()):
        stretches.sort(reverse=True)
        print(name, 'over 500 ms:', sum(1 for s in stretches if s[0] > 500), 'over 1000 ms:',
              sum(1 for s in stretches if s[0] > 1000), 'longest:', [(round(a), b) for a, b in stretches[:4]])


if __name__ == '__main__':
    main()
