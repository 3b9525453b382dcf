// Checks how CfGatewayClient.Gateway.request ends when no answer comes, so that a test can see it
// from outside (compile both files: javac -d out clients/java/*.java):
//
//   java -cp out RequestCheck HOST PORT NAME MUTE
//
// First a request to a name nobody registered: the gateway's failure must end it ("UNKNOWN <why>").
// Then a request to MUTE, an agent that takes messages and never answers, with a 1 s timeout:
// it must end in time ("TIMEOUT <why>"). A message of another conversation that came meanwhile
// must still be there to receive ("KEPT <content>"). Exit 0 when all went as it should, else 1.

import java.io.IOException;

public class RequestCheck {
    private static boolean endsWithError(CfGatewayClient.Gateway gw, String receiver, double timeout, String tag) {
        try {
            Object answer = gw.request(receiver, "(exec Player kick :playerNumber 9 :whichTeam our :power 10)", timeout);
            System.out.println(tag + " ANSWERED " + answer);
            return false;
        } catch (IOException exc) {
            System.out.println(tag + " " + exc.getMessage());
            return true;
        }
    }

    public static void main(String[] args) throws IOException {
        try (CfGatewayClient.Gateway gw = new CfGatewayClient.Gateway(args[0], Integer.parseInt(args[1]), args[2], null)) {
            gw.command("(register :service-class Monitoring :lease 10.0)", "registered");  // others may send to it
            boolean ok = endsWithError(gw, "nobody_registered_this", 30.0, "UNKNOWN");
            ok = endsWithError(gw, args[3], 1.0, "TIMEOUT") && ok;
            Object kept = gw.receive();
            System.out.println("KEPT " + CfGatewayClient.Sexp.text(CfGatewayClient.Sexp.param(kept, "content")));
            System.out.flush();
            if (!ok) System.exit(1);
        }
    }
}
