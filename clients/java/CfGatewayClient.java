// A Common Framework agent in Java (JDK 17, standard library only), over the TCP gateway.
//
//   java CfGatewayClient.java HOST PORT NAME [TOKEN]
//
// It says hello, registers as a PlayerDecision, looks up a Kick provider,
// runs a fipa-request with it, then serves one fipa-request from any agent
// (ROS or TCP) and says bye. Copy the Sexp and Gateway classes into your agent.
// The protocol is in docs/gateway-protocol.md.

import java.io.*;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.util.*;

public class CfGatewayClient {

    /** S-expressions: lists are List<Object>, strings are Str, numbers Long/Double, words String. */
    public static final class Sexp {
        public record Str(String value) {}

        private final String text;
        private int pos;

        private Sexp(String text) { this.text = text; }

        public static Object read(String text) {
            Sexp reader = new Sexp(text);
            Object value = reader.item();
            reader.space();
            if (reader.pos != text.length()) throw new IllegalArgumentException("trailing text at " + reader.pos);
            return value;
        }

        private void space() {
            while (pos < text.length() && Character.isWhitespace(text.charAt(pos))) pos++;
        }

        private Object item() {
            space();
            if (pos >= text.length()) throw new IllegalArgumentException("unexpected end of input");
            char c = text.charAt(pos);
            if (c == '(') {
                pos++;
                List<Object> list = new ArrayList<>();
                while (true) {
                    space();
                    if (pos >= text.length()) throw new IllegalArgumentException("unclosed (");
                    if (text.charAt(pos) == ')') { pos++; return list; }
                    list.add(item());
                }
            }
            if (c == '"') {
                StringBuilder sb = new StringBuilder();
                pos++;
                while (pos < text.length() && text.charAt(pos) != '"') {
                    char ch = text.charAt(pos++);
                    if (ch == '\\' && pos < text.length()) {
                        char e = text.charAt(pos++);
                        sb.append(switch (e) { case 'n' -> '\n'; case 't' -> '\t'; case 'r' -> '\r'; default -> e; });
                    } else sb.append(ch);
                }
                pos++;
                return new Str(sb.toString());
            }
            int start = pos;
            while (pos < text.length() && !Character.isWhitespace(text.charAt(pos)) && "()\"".indexOf(text.charAt(pos)) < 0) pos++;
            String word = text.substring(start, pos);
            try { return Long.parseLong(word); } catch (NumberFormatException e) { /* not an integer */ }
            if (word.matches("[-+]?(\\d+\\.\\d*|\\.\\d+|\\d+)([eE][-+]?\\d+)?")) return Double.parseDouble(word);
            return word;
        }

        public static String quote(String s) {
            return "\"" + s.replace("\\", "\\\\").replace("\"", "\\\"").replace("\n", "\\n") + "\"";
        }

        /** The value after :key in a list such as (head :key value ...), or null. */
        public static Object param(Object sexp, String key) {
            if (!(sexp instanceof List<?> list)) return null;
            for (int i = 1; i + 1 < list.size(); i++) {
                if ((":" + key).equals(list.get(i))) return list.get(i + 1);
            }
            return null;
        }

        public static String text(Object value) {
            if (value instanceof Str s) return s.value();
            return value == null ? null : value.toString();
        }
    }

    /** One connection to the gateway. */
    public static final class Gateway implements Closeable {
        private final Socket socket;
        private final InputStream in;
        private final ByteArrayOutputStream partial = new ByteArrayOutputStream();  // a line read in part
        private final Writer out;
        private final Deque<Object> inbox = new ArrayDeque<>();
        public final String name;
        private int conversations = 0;

        public Gateway(String host, int port, String name, String token) throws IOException {
            this.name = name;
            socket = new Socket(host, port);
            in = new BufferedInputStream(socket.getInputStream());
            out = new OutputStreamWriter(socket.getOutputStream(), StandardCharsets.UTF_8);
            String hello = "(hello :name " + name + (token == null ? "" : " :token " + Sexp.quote(token)) + ")";
            command(hello, "welcome");
        }

        public void send(String line) throws IOException {
            out.write(line + "\n");
            out.flush();
        }

        /**
         * The next line, split by us: a BufferedReader loses the part of a line it had read when
         * a request's timeout interrupts it, and the next line would then start mid-message.
         */
        private Object readLine() throws IOException {
            while (true) {
                int b = in.read();  // a timeout leaves what came so far in partial
                if (b < 0) throw new EOFException("gateway closed the connection");
                if (b == '\n') {
                    String line = partial.toString(StandardCharsets.UTF_8);
                    partial.reset();
                    return Sexp.read(line);
                }
                partial.write(b);
            }
        }

        private static String head(Object sexp) {
            return sexp instanceof List<?> l && !l.isEmpty() ? String.valueOf(l.get(0)) : "";
        }

        /** Send a command and wait for its answer; ACL messages arriving meanwhile are kept. */
        public Object command(String line, String expect) throws IOException {
            send(line);
            while (true) {
                Object answer = readLine();
                String h = head(answer);
                throwIfRefused(answer);
                if (h.equals(expect)) return answer;
                if (Sexp.param(answer, "sender") != null) inbox.add(answer);
            }
        }

        public void register(String serviceClass, String team, int player) throws IOException {
            command("(register :service-class " + serviceClass + " :team " + Sexp.quote(team) + " :player " + player
                    + " :lease 2.0)", "registered");
        }

        public List<String> lookup(String serviceClass) throws IOException {
            Object answer = command("(lookup :service-class " + serviceClass + ")", "providers");
            List<String> names = new ArrayList<>();
            for (Object p : ((List<?>) answer).subList(1, ((List<?>) answer).size()))
                names.add(Sexp.text(Sexp.param(p, "name")));
            return names;
        }

        /** The next ACL message addressed to us. */
        public Object receive() throws IOException {
            if (!inbox.isEmpty()) return inbox.poll();
            while (true) {
                Object msg = readLine();
                if (Sexp.param(msg, "sender") != null) return msg;
                // The gateway's own failure may be about a message we sent (an unknown receiver):
                // whoever waits for its answer must hear it.
                throwIfRefused(msg);
            }
        }

        /** The gateway's own failure, not-understood or error (it has no :sender) as an IOException. */
        private static void throwIfRefused(Object msg) throws IOException {
            String h = head(msg);
            if (Sexp.param(msg, "sender") == null
                    && (h.equals("failure") || h.equals("not-understood") || h.equals("error")))
                throw new IOException(h + ": " + Sexp.text(Sexp.param(msg, "reason")));
        }

        /** A fipa-request to its final answer (an agree is skipped); IOException with none in 30 s. */
        public Object request(String receiver, String content) throws IOException {
            return request(receiver, content, 30.0);
        }

        /**
         * A fipa-request to its final answer (an agree is skipped). The request carries
         * :reply-by now + timeout (wall clock); with no answer by then, IOException.
         */
        public Object request(String receiver, String content, double timeout) throws IOException {
            String cid = name + "-c" + (++conversations);
            long span = Math.max(1, Math.round(timeout * 1000));
            String replyBy = FIPA_TIME.format(java.time.Instant.now().plusMillis(span));
            send("(request :receiver (set (agent-identifier :name " + receiver + ")) :content " + Sexp.quote(content)
                    + " :language cf-lang :ontology robocup-soccer :protocol fipa-request :conversation-id " + cid
                    + " :reply-with " + cid + "-r1 :reply-by " + replyBy + ")");
            long deadline = System.nanoTime() + span * 1_000_000L;  // our own wait: monotonic
            List<Object> others = new ArrayList<>();
            try {
                while (true) {
                    long left = (deadline - System.nanoTime()) / 1_000_000L;
                    if (left <= 0) throw new java.net.SocketTimeoutException();
                    socket.setSoTimeout((int) Math.min(left, Integer.MAX_VALUE));
                    Object msg = receive();
                    if (!cid.equals(Sexp.text(Sexp.param(msg, "conversation-id")))) { others.add(msg); continue; }
                    if (!head(msg).equals("agree")) return msg;
                }
            } catch (java.net.SocketTimeoutException timedOut) {
                throw new IOException("no answer from " + receiver + " within " + timeout + " s");
            } finally {
                socket.setSoTimeout(0);
                inbox.addAll(others);
            }
        }

        private static final java.time.format.DateTimeFormatter FIPA_TIME =
                java.time.format.DateTimeFormatter.ofPattern("yyyyMMdd'T'HHmmssSSS'Z'").withZone(java.time.ZoneOffset.UTC);

        /** Answer a request: agree, then inform with a result. */
        public void reply(Object request, String performative, String content) throws IOException {
            Object sender = Sexp.param(Sexp.param(request, "sender"), "name");
            Object cid = Sexp.param(request, "conversation-id");
            Object replyWith = Sexp.param(request, "reply-with");
            send("(" + performative + " :receiver (set (agent-identifier :name " + Sexp.text(sender) + "))"
                    + (content == null ? "" : " :content " + Sexp.quote(content))
                    + " :protocol fipa-request :conversation-id " + Sexp.text(cid)
                    + (replyWith == null ? "" : " :in-reply-to " + Sexp.text(replyWith)) + ")");
        }

        @Override
        public void close() throws IOException {
            try { command("(bye)", "bye"); } finally { socket.close(); }
        }
    }

    public static void main(String[] args) throws Exception {
        String host = args[0];
        int port = Integer.parseInt(args[1]);
        String name = args[2];
        String token = args.length > 3 ? args[3] : null;
        try (Gateway gw = new Gateway(host, port, name, token)) {
            System.out.println("CONNECTED " + name);
            gw.register("PlayerDecision", "blue", 9);
            System.out.println("REGISTERED");
            List<String> providers = gw.lookup("Kick");
            System.out.println("PROVIDERS " + providers);
            Object answer = gw.request(providers.get(0),
                    "(exec Player kick :playerNumber 9 :whichTeam our :power 70 :direction 0.2)");
            System.out.println("ANSWER " + head(answer) + " " + Sexp.text(Sexp.param(answer, "content")));
            System.out.println("SERVING");
            System.out.flush();
            Object request = gw.receive();
            gw.reply(request, "agree", null);
            gw.reply(request, "inform", "(done-by-java " + Sexp.text(Sexp.param(request, "content")).length() + ")");
            System.out.println("SERVED " + Sexp.text(Sexp.param(Sexp.param(request, "sender"), "name")));
        }
        System.out.println("BYE");
    }

    private static String head(Object sexp) {
        return sexp instanceof List<?> l && !l.isEmpty() ? String.valueOf(l.get(0)) : "";
    }
}
