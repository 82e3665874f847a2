//! Who may talk to the tuning server: a request must carry the session's token and name the
//! server itself in its `Host` (and `Origin`, when a browser sends one), so that neither another
//! site open in the browser nor a name rebound to 127.0.0.1 can reach it.

/// Why a request is refused.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Refusal {
    /// No token, or not the session's (HTTP 401).
    Token,
    /// The `Host` header names another server (HTTP 403).
    Host(String),
    /// The `Origin` header names another site (HTTP 403).
    Origin(String),
}

impl Refusal {
    /// The HTTP status the refusal is answered with.
    #[must_use]
    pub fn status(&self) -> u16 {
        match self {
            Refusal::Token => 401,
            Refusal::Host(_) | Refusal::Origin(_) => 403,
        }
    }

    /// One line for the client.
    #[must_use]
    pub fn message(&self) -> String {
        match self {
            Refusal::Token => {
                "this server needs the token printed when it started: open the URL it printed"
                    .to_string()
            }
            Refusal::Host(host) => format!("Host {host:?} is not this server"),
            Refusal::Origin(origin) => format!("requests from {origin:?} are not accepted"),
        }
    }
}

/// The checks every request passes: its token, its `Host` and its `Origin`.
#[derive(Clone, Debug)]
pub struct Guard {
    token: String,
    /// The `host:port` forms a request may name the server by.
    hosts: Vec<String>,
}

impl Guard {
    /// A guard for a server listening on `port` at the host names `names` (`127.0.0.1`,
    /// `localhost`, or the address given to `--bind`), that requires `token`.
    #[must_use]
    pub fn new(token: String, names: &[String], port: u16) -> Self {
        let hosts = names.iter().map(|name| format!("{name}:{port}")).collect();
        Self { token, hosts }
    }

    /// Checks a request: `host` and `origin` are its headers of those names (`None` when
    /// absent), `token` the token it carries (its `X-Glint-Token` header or its `token` query
    /// parameter). A request without `Host` is refused (HTTP/1.1 requires it); one without
    /// `Origin` is allowed (browsers send it on every request that could change something,
    /// and a non-browser client has no site to speak for). The token is compared in time
    /// independent of where it first differs.
    pub fn check(
        &self,
        host: Option<&str>,
        origin: Option<&str>,
        token: Option<&str>,
    ) -> Result<(), Refusal> {
        let host = host.unwrap_or_default();
        if !self.hosts.iter().any(|h| h.eq_ignore_ascii_case(host)) {
            return Err(Refusal::Host(host.to_string()));
        }
        if let Some(origin) = origin {
            let own = origin
                .strip_prefix("http://")
                .is_some_and(|rest| self.hosts.iter().any(|h| h.eq_ignore_ascii_case(rest)));
            if !own {
                return Err(Refusal::Origin(origin.to_string()));
            }
        }
        match token {
            Some(token) if same_secret(token.as_bytes(), self.token.as_bytes()) => Ok(()),
            _ => Err(Refusal::Token),
        }
    }
}

/// Whether `a` and `b` are equal, looking at every byte whatever the first difference.
fn same_secret(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

/// A new random token: 128 bits from the operating system, as 32 hex digits.
pub fn new_token() -> Result<String, getrandom::Error> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes)?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn guard() -> Guard {
        let names = ["127.0.0.1".to_string(), "localhost".to_string()];
        Guard::new("0123456789abcdef".to_string(), &names, 8123)
    }

    #[test]
    fn the_server_s_own_host_and_origin_with_the_token_pass() {
        let g = guard();
        let token = Some("0123456789abcdef");
        assert_eq!(g.check(Some("127.0.0.1:8123"), None, token), Ok(()));
        assert_eq!(
            g.check(Some("localhost:8123"), Some("http://localhost:8123"), token),
            Ok(())
        );
    }

    #[test]
    fn another_host_origin_port_or_token_is_refused() {
        let g = guard();
        let token = Some("0123456789abcdef");
        let host = Some("127.0.0.1:8123");
        assert!(matches!(
            g.check(Some("evil.example:8123"), None, token),
            Err(Refusal::Host(_))
        ));
        assert!(matches!(
            g.check(Some("127.0.0.1:9999"), None, token),
            Err(Refusal::Host(_))
        ));
        assert!(matches!(g.check(None, None, token), Err(Refusal::Host(_))));
        for origin in [
            "http://evil.example",
            "https://127.0.0.1:8123",
            "null",
            "http://127.0.0.1:81234",
        ] {
            assert!(
                matches!(g.check(host, Some(origin), token), Err(Refusal::Origin(_))),
                "{origin}"
            );
        }
        for wrong in [
            None,
            Some(""),
            Some("0123456789abcdeF"),
            Some("0123456789abcde"),
            // Two bytes swapped: their differences are alike, and must not cancel.
            Some("1023456789abcdef"),
            Some("0123456789abcdfe"),
        ] {
            assert_eq!(g.check(host, None, wrong), Err(Refusal::Token), "{wrong:?}");
        }
    }

    #[test]
    fn a_refusal_says_what_was_refused_in_one_line() {
        let g = guard();
        let token = Some("0123456789abcdef");
        let refusals = [
            g.check(Some("evil.example:8123"), None, token),
            g.check(Some("127.0.0.1:8123"), Some("http://evil.example"), token),
            g.check(Some("127.0.0.1:8123"), None, Some("nope")),
        ]
        .map(Result::unwrap_err);
        let messages = refusals.clone().map(|r| r.message());
        assert!(messages[0].contains("\"evil.example:8123\" is not this server"));
        assert!(messages[1].contains("\"http://evil.example\" are not accepted"));
        assert!(messages[2].contains("token printed when it started"));
        for m in &messages {
            assert!(!m.contains('\n'), "{m}");
        }
        assert_eq!(refusals.map(|r| r.status()), [403, 403, 401]);
    }

    #[test]
    fn tokens_are_new_each_time() {
        let (a, b) = (new_token().unwrap(), new_token().unwrap());
        assert_eq!(a.len(), 32);
        assert!(a.chars().all(|c| c.is_ascii_hexdigit()));
        assert_ne!(a, b);
    }
}
