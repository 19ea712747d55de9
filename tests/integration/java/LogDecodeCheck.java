// Reads an LCM log written by C++ rgnav processes with lcm.logging.Log and decodes every event
// on the contract channels with the rgnav Java class of its type, as lcm-spy would. Compares
// with the records the C++ publisher wrote (tests/support/message_records.h):
//   - the event bytes equal the bytes C++ sent,
//   - the fingerprint in the bytes equals the Java class's LCM_FINGERPRINT,
//   - re-encoding the decoded Java object gives the same bytes,
//   - the canonical JSON of the Java object equals the C++ to_json() of the message
//     (keys sorted, floats as IEEE bit patterns, 8-bit integers unsigned).
// Usage: LogDecodeCheck LOGFILE RECORDS CHANNEL_PREFIX
// Exit status 0 when everything matches, 1 with a message naming the first mismatch.
import java.io.BufferedReader;
import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.io.EOFException;
import java.io.FileReader;
import java.lang.reflect.Array;
import java.lang.reflect.Field;
import java.lang.reflect.Modifier;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Comparator;
import java.util.List;

import lcm.logging.Log;
import lcm.lcm.LCMEncodable;

public class LogDecodeCheck
{
    static final class Record
    {
        String channel, type, hex, json;
    }

    public static void main(String[] args) throws Exception
    {
        if (args.length != 3) {
            System.err.println("usage: LogDecodeCheck LOGFILE RECORDS CHANNEL_PREFIX");
            System.exit(2);
        }
        // Referenced statically so this program only compiles against the rgnav jar.
        if (rgnav.laser_scan_t.LCM_FINGERPRINT == 0) fail("laser_scan_t has no fingerprint");

        List<Record> sent = readRecords(args[1]);
        String prefix = args[2];
        Log log = new Log(args[0], "r");
        int index = 0;
        int otherEvents = 0;
        while (true) {
            Log.Event ev;
            try {
                ev = log.readNext();
            } catch (EOFException e) {
                break;
            }
            if (!ev.channel.startsWith(prefix)) {
                ++otherEvents;
                continue;
            }
            if (index >= sent.size()) fail("log has more contract events than C++ sent: " + ev.channel);
            Record r = sent.get(index);
            String where = "event " + index + " on " + ev.channel;
            if (!ev.channel.equals(r.channel)) fail(where + ": C++ sent it on " + r.channel);
            if (!hex(ev.data).equals(r.hex)) fail(where + ": bytes differ from what C++ sent");

            Class<?> cls = Class.forName("rgnav." + r.type);
            long classFingerprint = cls.getField("LCM_FINGERPRINT").getLong(null);
            long wireFingerprint = ByteBuffer.wrap(ev.data, 0, 8).getLong();
            if (classFingerprint != wireFingerprint)
                fail(where + ": fingerprint " + Long.toHexString(wireFingerprint) + " != rgnav." + r.type
                     + ".LCM_FINGERPRINT " + Long.toHexString(classFingerprint));
            Object msg = cls.getConstructor(byte[].class).newInstance((Object) ev.data);

            ByteArrayOutputStream bytes = new ByteArrayOutputStream();
            ((LCMEncodable) msg).encode(new DataOutputStream(bytes));
            if (!Arrays.equals(bytes.toByteArray(), ev.data)) fail(where + ": Java re-encoding differs");

            StringBuilder json = new StringBuilder();
            toJson(json, msg);
            if (!json.toString().equals(r.json))
                fail(where + ": field values differ\n  C++:  " + r.json + "\n  Java: " + json);
            ++index;
        }
        log.close();
        if (index != sent.size()) fail("log has " + index + " contract events, C++ sent " + sent.size());
        System.out.println("OK: " + index + " events decoded by the rgnav Java classes and equal to C++ ("
                           + otherEvents + " other events skipped)");
    }

    static void fail(String why)
    {
        System.err.println("FAIL: " + why);
        System.exit(1);
    }

    static List<Record> readRecords(String path) throws Exception
    {
        List<Record> out = new ArrayList<>();
        try (BufferedReader in = new BufferedReader(new FileReader(path, StandardCharsets.UTF_8))) {
            for (String line; (line = in.readLine()) != null;) {
                String[] p = line.split("\t", -1);
                if (p.length != 4) fail(path + ": malformed line");
                Record r = new Record();
                r.channel = p[0];
                r.type = p[1];
                r.hex = p[2];
                r.json = p[3];
                out.add(r);
            }
        }
        return out;
    }

    static String hex(byte[] data)
    {
        StringBuilder sb = new StringBuilder(data.length * 2);
        for (byte b : data) sb.append(Character.forDigit((b >> 4) & 15, 16)).append(Character.forDigit(b & 15, 16));
        return sb.toString();
    }

    // The same canonical form as the generated C++ to_json().
    static void toJson(StringBuilder sb, Object v) throws Exception
    {
        if (v instanceof LCMEncodable) {
            List<Field> fields = new ArrayList<>();
            for (Field f : v.getClass().getFields())
                if (!Modifier.isStatic(f.getModifiers())) fields.add(f);
            fields.sort(Comparator.comparing(Field::getName));
            sb.append('{');
            for (int i = 0; i < fields.size(); ++i) {
                if (i > 0) sb.append(',');
                sb.append('"').append(fields.get(i).getName()).append("\":");
                toJson(sb, fields.get(i).get(v));
            }
            sb.append('}');
        } else if (v != null && v.getClass().isArray()) {
            sb.append('[');
            for (int i = 0; i < Array.getLength(v); ++i) {
                if (i > 0) sb.append(',');
                toJson(sb, Array.get(v, i));
            }
            sb.append(']');
        } else if (v instanceof Float) {
            sb.append(Integer.toUnsignedString(Float.floatToRawIntBits((Float) v)));
        } else if (v instanceof Double) {
            sb.append(Long.toUnsignedString(Double.doubleToRawLongBits((Double) v)));
        } else if (v instanceof Byte) {
            sb.append(((Byte) v) & 0xff);
        } else if (v instanceof Boolean) {
            sb.append(((Boolean) v) ? "true" : "false");
        } else if (v instanceof Short || v instanceof Integer || v instanceof Long) {
            sb.append(v.toString());
        } else if (v instanceof String) {
            sb.append('"');
            for (byte b : ((String) v).getBytes(StandardCharsets.UTF_8)) {
                int c = b & 0xff;
                if (c == '"' || c == '\\') sb.append('\\').append((char) c);
                else if (c < 0x20 || c >= 0x7f) sb.append(String.format("\\u00%02x", c));
                else sb.append((char) c);
            }
            sb.append('"');
        } else {
            throw new IllegalArgumentException("unexpected field value " + v);
        }
    }
}
