//! FNV-1a (64 bits) digests, written as 16 hex digits: what a roadmap file's
//! fingerprint and checksum are made of.

/// The FNV-1a offset basis.
const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
/// The FNV-1a prime.
const FNV_PRIME: u64 = 0x0100_0000_01b3;

/// A running FNV-1a digest.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Digest(u64);

impl Default for Digest {
    fn default() -> Self {
        Self(FNV_OFFSET)
    }
}

impl Digest {
    /// The digest of `bytes` alone, as hex.
    pub fn hex_of(bytes: &[u8]) -> String {
        Self::default().update(bytes).hex()
    }

    /// Continues the digest with `bytes`.
    pub fn update(mut self, bytes: &[u8]) -> Self {
        for &b in bytes {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(FNV_PRIME);
        }
        self
    }

    /// The digest so far as 16 hex digits.
    pub fn hex(self) -> String {
        format!("{:016x}", self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::Digest;

    #[test]
    fn digests_are_fnv1a_64() {
        assert_eq!(Digest::hex_of(b""), "cbf29ce484222325");
        assert_eq!(Digest::hex_of(b"a"), "af63dc4c8601ec8c");
        let split = Digest::default().update(b"foo").update(b"bar").hex();
        assert_eq!(split, Digest::hex_of(b"foobar"));
    }
}
