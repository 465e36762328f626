//! The guards every request passes.

use super::*;

#[test]
fn only_a_loopback_host_at_this_port_is_answered() {
    assert!(loopback_host("127.0.0.1:8123", 8123));
    assert!(loopback_host("localhost:8123", 8123));
    assert!(loopback_host("[::1]:8123", 8123));
    // A name rebound to 127.0.0.1 by another site, another port, no port, an empty header.
    assert!(!loopback_host("evil.example:8123", 8123));
    assert!(!loopback_host("127.0.0.1.evil.example:8123", 8123));
    assert!(!loopback_host("127.0.0.1:8124", 8123));
    assert!(!loopback_host("127.0.0.1", 8123));
    assert!(!loopback_host("", 8123));
}

#[test]
fn the_token_is_read_from_the_query_and_compared_whole() {
    assert_eq!(query_token("/api/evaluate?token=abc&x=1"), Some("abc"));
    assert_eq!(query_token("/?x=1&token=abc"), Some("abc"));
    assert_eq!(query_token("/api/evaluate"), None);
    assert!(same("abc", "abc"));
    assert!(!same("abc", "abd"));
    assert!(!same("abc", "abcd"));
    let t = token().unwrap();
    assert_eq!(t.len(), 32);
    assert_ne!(t, token().unwrap());
}

#[test]
fn a_state_with_an_unknown_key_is_refused_in_words() {
    let e = parse::<State>(br#"{"effect": []}"#).unwrap_err();
    assert!(e.contains("unknown field `effect`"), "{e}");
    assert!(parse::<State>(b"{not json").is_err());
    assert_eq!(parse::<State>(br#"{"effects": ["a:b=1"]}"#).unwrap().effects, ["a:b=1"]);
}
