//! The URL a student opens: the classroom's page with the data server's address and the WebGL
//! renderer (WebGPU fails in software rendering: "createBuffer too large"), and optionally a
//! theme.

use std::net::IpAddr;

/// `s` with everything but unreserved URL characters percent-encoded.
fn encode(s: &str) -> String {
    s.bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'_' | b'.' | b'~' => {
                (b as char).to_string()
            }
            _ => format!("%{b:02X}"),
        })
        .collect()
}

/// `http://ADDRESS:PORT` (IPv6 in brackets).
pub fn origin(address: IpAddr, port: u16) -> String {
    match address {
        IpAddr::V4(a) => format!("http://{a}:{port}"),
        IpAddr::V6(a) => format!("http://[{a}]:{port}"),
    }
}

/// The page at `address:port` showing the data at `data_url`, WebGL, `theme` if given.
pub fn page_url(address: IpAddr, port: u16, data_url: &str, theme: Option<&str>) -> String {
    let mut url = format!(
        "{}/?url={}&renderer=webgl",
        origin(address, port),
        encode(data_url)
    );
    if let Some(t) = theme {
        url.push_str("&theme=");
        url.push_str(&encode(t));
    }
    url
}
