//! The few rules of ROS 2's CDR encoding (XCDR1, little endian) that SMUG's messages
//! need: a 4-byte encapsulation header `00 01 00 00`, then each primitive aligned to its
//! own size counted from the end of that header, strings as a `u32` length (NUL
//! included), the bytes and a NUL, sequences as a `u32` count and their elements.

/// The encapsulation header: plain CDR, little endian, no options.
pub const HEADER: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// Why CDR bytes could not be read.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum CdrError {
    /// The bytes do not start with [`HEADER`].
    #[error("not little-endian CDR: the encapsulation header is {0:02x?}")]
    Header(Vec<u8>),
    /// The bytes end before a value.
    #[error("truncated at byte {at}: {need} more bytes needed")]
    Truncated {
        /// Offset after the header.
        at: usize,
        /// Bytes the value needs.
        need: usize,
    },
    /// A string is not NUL-terminated UTF-8.
    #[error("string at byte {at} is not NUL-terminated UTF-8")]
    BadString {
        /// Offset after the header.
        at: usize,
    },
}

/// Writes CDR bytes, header first.
#[derive(Debug)]
pub struct CdrWriter {
    bytes: Vec<u8>,
}

impl Default for CdrWriter {
    fn default() -> Self {
        Self {
            bytes: HEADER.to_vec(),
        }
    }
}

impl CdrWriter {
    /// Pads with zeros until the next value of `size` bytes is aligned.
    fn align(&mut self, size: usize) {
        while !(self.bytes.len() - HEADER.len()).is_multiple_of(size) {
            self.bytes.push(0);
        }
    }

    /// An aligned primitive's little-endian bytes.
    fn primitive<const N: usize>(&mut self, le: [u8; N]) {
        self.align(N);
        self.bytes.extend_from_slice(&le);
    }

    /// A `uint8` (also a `bool`, as 0 or 1).
    pub fn u8(&mut self, v: u8) {
        self.bytes.push(v);
    }

    /// An `int8`.
    pub fn i8(&mut self, v: i8) {
        self.primitive(v.to_le_bytes());
    }

    /// A `bool`.
    pub fn bool(&mut self, v: bool) {
        self.u8(u8::from(v));
    }

    /// An `int32`.
    pub fn i32(&mut self, v: i32) {
        self.primitive(v.to_le_bytes());
    }

    /// A `uint32`.
    pub fn u32(&mut self, v: u32) {
        self.primitive(v.to_le_bytes());
    }

    /// A `float32`.
    pub fn f32(&mut self, v: f32) {
        self.primitive(v.to_le_bytes());
    }

    /// A `float64`.
    pub fn f64(&mut self, v: f64) {
        self.primitive(v.to_le_bytes());
    }

    /// A sequence's element count (saturating at `u32::MAX`, far beyond any grid SMUG
    /// holds in memory).
    pub fn len(&mut self, n: usize) {
        self.u32(u32::try_from(n).unwrap_or(u32::MAX));
    }

    /// A `string`: length with the NUL, bytes, NUL.
    pub fn string(&mut self, s: &str) {
        self.len(s.len() + 1);
        self.bytes.extend_from_slice(s.as_bytes());
        self.bytes.push(0);
    }

    /// A `uint8[]` or `int8[]`'s bytes after its count.
    pub fn byte_sequence(&mut self, data: &[u8]) {
        self.len(data.len());
        self.bytes.extend_from_slice(data);
    }

    /// The bytes written, header first.
    pub fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }
}

/// Reads CDR bytes written by [`CdrWriter`] (or any little-endian XCDR1 writer).
#[derive(Debug)]
pub struct CdrReader<'a> {
    body: &'a [u8],
    at: usize,
}

impl<'a> CdrReader<'a> {
    /// A reader of `bytes`, which must start with [`HEADER`].
    pub fn new(bytes: &'a [u8]) -> Result<Self, CdrError> {
        match bytes.split_at_checked(HEADER.len()) {
            Some((head, body)) if head == HEADER => Ok(Self { body, at: 0 }),
            _ => Err(CdrError::Header(bytes.iter().take(4).copied().collect())),
        }
    }

    /// The next `n` bytes after aligning to `align`.
    fn take(&mut self, align: usize, n: usize) -> Result<&'a [u8], CdrError> {
        let start = self.at.next_multiple_of(align);
        let end = start.checked_add(n).filter(|&end| end <= self.body.len());
        let end = end.ok_or(CdrError::Truncated { at: start, need: n })?;
        self.at = end;
        Ok(&self.body[start..end])
    }

    /// An aligned primitive's bytes.
    fn primitive<const N: usize>(&mut self) -> Result<[u8; N], CdrError> {
        let bytes = self.take(N, N)?;
        Ok(bytes.try_into().expect("take returns N bytes"))
    }

    /// A `uint8`.
    pub fn u8(&mut self) -> Result<u8, CdrError> {
        Ok(self.take(1, 1)?[0])
    }

    /// An `int8`.
    pub fn i8(&mut self) -> Result<i8, CdrError> {
        self.primitive().map(i8::from_le_bytes)
    }

    /// A `bool` (any non-zero byte is true).
    pub fn bool(&mut self) -> Result<bool, CdrError> {
        Ok(self.u8()? != 0)
    }

    /// An `int32`.
    pub fn i32(&mut self) -> Result<i32, CdrError> {
        self.primitive().map(i32::from_le_bytes)
    }

    /// A `uint32`.
    pub fn u32(&mut self) -> Result<u32, CdrError> {
        self.primitive().map(u32::from_le_bytes)
    }

    /// A `float32`.
    pub fn f32(&mut self) -> Result<f32, CdrError> {
        self.primitive().map(f32::from_le_bytes)
    }

    /// A `float64`.
    pub fn f64(&mut self) -> Result<f64, CdrError> {
        self.primitive().map(f64::from_le_bytes)
    }

    /// A sequence's element count.
    pub fn count(&mut self) -> Result<usize, CdrError> {
        Ok(self.u32()? as usize)
    }

    /// A `string`.
    pub fn string(&mut self) -> Result<String, CdrError> {
        let n = self.count()?;
        let at = self.at;
        let bytes = self.take(1, n)?;
        match bytes.split_last() {
            Some((0, text)) => std::str::from_utf8(text)
                .map(str::to_owned)
                .map_err(|_| CdrError::BadString { at }),
            _ => Err(CdrError::BadString { at }),
        }
    }

    /// A `uint8[]` or `int8[]`'s bytes.
    pub fn byte_sequence(&mut self) -> Result<Vec<u8>, CdrError> {
        let n = self.count()?;
        Ok(self.take(1, n)?.to_vec())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primitives_align_to_their_size_after_the_header() {
        let mut w = CdrWriter::default();
        w.u8(7);
        w.f64(1.0);
        w.i8(-1);
        w.u32(2);
        let bytes = w.into_bytes();
        #[rustfmt::skip]
        let expected = [
            0, 1, 0, 0,                         // header
            7, 0, 0, 0, 0, 0, 0, 0,             // u8, 7 bytes padding to 8
            0, 0, 0, 0, 0, 0, 0xf0, 0x3f,       // 1.0f64
            0xff, 0, 0, 0,                      // -1i8, padding to 4
            2, 0, 0, 0,                         // 2u32
        ];
        assert_eq!(bytes, expected);
        let mut r = CdrReader::new(&bytes).unwrap();
        assert_eq!(r.u8().unwrap(), 7);
        assert_eq!(r.f64().unwrap(), 1.0);
        assert_eq!(r.i8().unwrap(), -1);
        assert_eq!(r.u32().unwrap(), 2);
        assert!(matches!(
            r.u8(),
            Err(CdrError::Truncated { at: 24, need: 1 })
        ));
    }

    #[test]
    fn strings_count_their_nul() {
        let mut w = CdrWriter::default();
        w.string("map");
        w.string("");
        let bytes = w.into_bytes();
        let expected = [0, 1, 0, 0, 4, 0, 0, 0, b'm', b'a', b'p', 0, 1, 0, 0, 0, 0];
        assert_eq!(bytes, expected);
        let mut r = CdrReader::new(&bytes).unwrap();
        assert_eq!(r.string().unwrap(), "map");
        assert_eq!(r.string().unwrap(), "");
    }

    #[test]
    fn bad_bytes_are_errors() {
        assert!(matches!(
            CdrReader::new(&[0, 0, 0, 0]),
            Err(CdrError::Header(_))
        ));
        assert!(matches!(CdrReader::new(&[0, 1]), Err(CdrError::Header(_))));
        let mut no_nul = CdrReader::new(&[0, 1, 0, 0, 1, 0, 0, 0, b'x']).unwrap();
        assert_eq!(no_nul.string(), Err(CdrError::BadString { at: 4 }));
        let mut huge = CdrReader::new(&[0, 1, 0, 0, 0xff, 0xff, 0xff, 0xff]).unwrap();
        assert!(matches!(
            huge.byte_sequence(),
            Err(CdrError::Truncated { .. })
        ));
    }
}
