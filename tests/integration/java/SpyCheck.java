// Starts lcm-spy (lcm.spy.Spy, as deploy/cli/spy.sh does) in this JVM on a display (Xvfb in
// tests), then reads its channel table the way a person reads the window: every expected
// channel must be listed with the rgnav type name (not "?? <fingerprint>"), messages counted,
// and no undecodable messages. Saves a screenshot of the window and refuses a blank one.
//
// Usage: SpyCheck TIMEOUT_S SCREENSHOT.png CHANNEL=type[,CHANNEL=type...] [spy args...]
// Exit 0 when all expected channels are decoded, 1 otherwise (printing the table).
import java.awt.Component;
import java.awt.Container;
import java.awt.Frame;
import java.awt.Rectangle;
import java.awt.Robot;
import java.awt.image.BufferedImage;
import java.io.File;
import java.util.HashMap;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.atomic.AtomicReference;
import javax.imageio.ImageIO;
import javax.swing.JTable;
import javax.swing.SwingUtilities;
import javax.swing.table.TableModel;

public class SpyCheck
{
    public static void main(String[] args) throws Exception
    {
        if (args.length < 3) {
            System.err.println("usage: SpyCheck TIMEOUT_S SCREENSHOT.png CHANNEL=type,... [spy args...]");
            System.exit(2);
        }
        long deadline = System.currentTimeMillis() + 1000L * Long.parseLong(args[0]);
        String screenshot = args[1];
        Map<String, String> expected = new LinkedHashMap<>();
        for (String kv : args[2].split(",")) {
            String[] p = kv.split("=");
            expected.put(p[0], p[1]);
        }
        String[] spyArgs = new String[args.length - 3];
        System.arraycopy(args, 3, spyArgs, 0, spyArgs.length);

        lcm.spy.Spy.main(spyArgs);

        Map<String, String[]> rows = new HashMap<>();
        String verdict = "no spy window";
        while (System.currentTimeMillis() < deadline) {
            Thread.sleep(500);
            rows = readTable();
            verdict = judge(expected, rows);
            if (verdict == null) break;
        }
        // Let a few more messages arrive so the screenshot shows counts and rates.
        if (verdict == null) Thread.sleep(1500);
        Frame frame = spyFrame();
        if (frame != null) {
            Rectangle r = frame.getBounds();
            BufferedImage img = new Robot().createScreenCapture(r);
            ImageIO.write(img, "png", new File(screenshot));
            Set<Integer> colors = new HashSet<>();
            for (int y = 0; y < img.getHeight(); y += 2)
                for (int x = 0; x < img.getWidth(); x += 2) colors.add(img.getRGB(x, y));
            System.out.println("screenshot " + screenshot + ": " + r.width + "x" + r.height + ", " + colors.size()
                               + " colours");
            if (verdict == null && colors.size() < 8) verdict = "screenshot of the spy window is blank";
        }
        printTable(readTable());
        if (verdict != null) {
            System.err.println("FAIL: " + verdict);
            System.exit(1);
        }
        System.out.println("OK: " + expected.size() + " rgnav channels decoded by lcm-spy");
        System.exit(0);
    }

    // null when every expected channel is decoded as its type, else what is wrong.
    static String judge(Map<String, String> expected, Map<String, String[]> rows)
    {
        for (Map.Entry<String, String> e : expected.entrySet()) {
            String[] row = rows.get(e.getKey());
            if (row == null) return "channel " + e.getKey() + " not listed";
            if (!row[1].equals(e.getValue())) return "channel " + e.getKey() + " shown as '" + row[1] + "', not " + e.getValue();
            if (row[2].isEmpty() || Long.parseLong(row[2]) < 2) return "channel " + e.getKey() + " has too few messages";
            if (!row[7].trim().equals("0") && !row[7].trim().isEmpty())
                return "channel " + e.getKey() + " has undecodable messages: " + row[7];
        }
        return null;
    }

    static Frame spyFrame()
    {
        for (Frame f : Frame.getFrames())
            if (f.isShowing() && findTable(f) != null) return f;
        return null;
    }

    static JTable findTable(Component c)
    {
        if (c instanceof JTable) return (JTable) c;
        if (c instanceof Container)
            for (Component child : ((Container) c).getComponents()) {
                JTable t = findTable(child);
                if (t != null) return t;
            }
        return null;
    }

    // Channel -> the row's cells as displayed, read on the Swing thread.
    static Map<String, String[]> readTable() throws Exception
    {
        AtomicReference<Map<String, String[]>> out = new AtomicReference<>(new HashMap<>());
        SwingUtilities.invokeAndWait(() -> {
            Frame f = spyFrame();
            if (f == null) return;
            TableModel m = findTable(f).getModel();
            Map<String, String[]> rows = new HashMap<>();
            for (int r = 0; r < m.getRowCount(); ++r) {
                String[] cells = new String[m.getColumnCount()];
                for (int c = 0; c < cells.length; ++c) {
                    Object v = m.getValueAt(r, c);
                    cells[c] = v == null ? "" : v.toString();
                }
                rows.put(cells[0], cells);
            }
            rows.put("#columns", columnNames(m));
            out.set(rows);
        });
        return out.get();
    }

    static String[] columnNames(TableModel m)
    {
        String[] names = new String[m.getColumnCount()];
        for (int c = 0; c < names.length; ++c) names[c] = m.getColumnName(c);
        return names;
    }

    static void printTable(Map<String, String[]> rows)
    {
        String[] header = rows.get("#columns");
        if (header != null) System.out.println(String.join(" | ", header));
        for (Map.Entry<String, String[]> e : rows.entrySet())
            if (!e.getKey().equals("#columns")) System.out.println(String.join(" | ", e.getValue()));
    }
}
