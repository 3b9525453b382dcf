// Checks that a request's timeout in the middle of a line loses nothing, so that a test can see
// it from outside (compile both files: javac -d out clients/java/*.java):
//
//   java -cp out SplitLineCheck HOST PORT NAME
//
// It says hello and sends a request with a 1 s timeout. The peer answers with the first half of a
// message of another conversation and the rest only later, so the timeout comes while half a line
// has been read ("TIMEOUT <why>"). That message must then be received whole ("KEPT <content>").
// Exit 0 when it was, else 1.

import java.io.IOException;

public class SplitLineCheck {
    public static void main(String[] args) throws IOException {
        try (CfGatewayClient.Gateway gw = new CfGatewayClient.Gateway(args[0], Integer.parseInt(args[1]), args[2], null)) {
            try {
                Object answer = gw.request("slow_peer", "(val Game time)", 1.0);
                System.out.println("ANSWERED " + answer);
                System.exit(1);
            } catch (IOException exc) {
                System.out.println("TIMEOUT " + exc.getMessage());
            }
            Object kept = gw.receive();
            System.out.println("KEPT " + CfGatewayClient.Sexp.text(CfGatewayClient.Sexp.param(kept, "content")));
            System.out.flush();
        }
    }
}
