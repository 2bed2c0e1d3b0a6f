//! Text files line by line, plain or gzip (told apart by gzip's magic
//! bytes, not by the file's name), each error naming the file and the line.
//!
//! A plain file's work is bounded by its size. A gzip stream's is bounded
//! by what it holds too: it may inflate to at most [`MAX_GZIP_RATIO`] times
//! the compressed bytes read so far, so that a small file of a few
//! compressed gigabytes of one repeated line (deflate inflates a byte to up
//! to 1032) is refused after a fraction of a second instead of being read
//! for minutes.

use std::cell::Cell;
use std::fs::File;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::rc::Rc;

use flate2::read::MultiGzDecoder;

use crate::error::{CovmapError, Result};

/// The longest line a reader takes, bytes: far above any real log's
/// (a CARMEN line of 1000 beams is some 10 kB), and a bound on what a file
/// without line breaks can make the reader allocate.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// The most bytes a gzip log inflates to per compressed byte read: 100.
/// Real logs of text numbers inflate 4 to 5 times (the CARMEN logs of the
/// shared data: 3.9 to 4.6, `python/tools/gzip_ratios.py`), a stream of one
/// repeated line over 300 times.
/// The check is made as the stream is read, against the compressed bytes
/// read so far (in blocks of 8 KiB, so that a file's first 800 kB inflate
/// whatever their ratio).
pub const MAX_GZIP_RATIO: u64 = 100;

/// The lines of one text file, numbered from 1.
pub(crate) struct Lines {
    reader: Box<dyn BufRead>,
    file: String,
    line: usize,
    buf: Vec<u8>,
}

/// The lines of the file at `path`, gunzipped if it starts with gzip's
/// magic bytes. Only a regular file is read: a device or a pipe is refused
/// before it is opened, so that it can neither block the open nor stream
/// without end.
pub(crate) fn open(path: &Path) -> Result<Lines> {
    let file = path.display().to_string();
    let metadata = std::fs::metadata(path).map_err(|e| CovmapError::io(&file, &e))?;
    if !metadata.is_file() {
        return Err(CovmapError::Io {
            file,
            reason: "not a regular file".to_owned(),
            errno: None,
        });
    }
    let file = File::open(path).map_err(|e| CovmapError::io(&file, &e))?;
    lines(file, &path.display().to_string())
}

/// The lines `reader` yields, gunzipped if they start with gzip's magic
/// bytes; `name` is the file's name in errors.
pub(crate) fn lines<R: Read + 'static>(reader: R, name: &str) -> Result<Lines> {
    let compressed = Rc::new(Cell::new(0u64));
    let counted = Counted {
        inner: reader,
        count: Rc::clone(&compressed),
    };
    let mut buffered = BufReader::new(counted);
    let head = buffered.fill_buf().map_err(|e| CovmapError::io(name, &e))?;
    let reader: Box<dyn BufRead> = if head.starts_with(&[0x1f, 0x8b]) {
        Box::new(BufReader::new(Bounded {
            inner: MultiGzDecoder::new(buffered),
            compressed,
            inflated: 0,
        }))
    } else {
        Box::new(buffered)
    };
    Ok(Lines {
        reader,
        file: name.to_string(),
        line: 0,
        buf: Vec::new(),
    })
}

/// A reader that counts the bytes read from it.
struct Counted<R> {
    inner: R,
    count: Rc<Cell<u64>>,
}

impl<R: Read> Read for Counted<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.count.set(self.count.get().saturating_add(n as u64));
        Ok(n)
    }
}

/// A gzip stream's inflated bytes, refused past [`MAX_GZIP_RATIO`] times
/// the compressed bytes read so far.
struct Bounded<R> {
    inner: R,
    compressed: Rc<Cell<u64>>,
    inflated: u64,
}

impl<R: Read> Read for Bounded<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.inflated = self.inflated.saturating_add(n as u64);
        let compressed = self.compressed.get();
        if self.inflated > compressed.saturating_mul(MAX_GZIP_RATIO) {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "the gzip stream inflates {} bytes from {compressed}, more than {MAX_GZIP_RATIO} \
                     times (a log inflates some 5 times): not a log covmap reads",
                    self.inflated
                ),
            ));
        }
        Ok(n)
    }
}

impl Lines {
    /// The next line without its line break, or `None` at the end.
    ///
    /// # Errors
    /// [`CovmapError::Parse`] for a line that is not UTF-8 or longer than
    /// [`MAX_LINE_BYTES`], or a read that fails (a corrupt gzip stream).
    pub(crate) fn next_line(&mut self) -> Result<Option<&str>> {
        self.buf.clear();
        self.line += 1;
        let limit = MAX_LINE_BYTES as u64 + 1;
        let read = (&mut self.reader)
            .take(limit)
            .read_until(b'\n', &mut self.buf)
            .map_err(|e| self.error(format!("read failed: {e}")))?;
        if read == 0 {
            return Ok(None);
        }
        if self.buf.len() > MAX_LINE_BYTES {
            return Err(self.error(format!("line longer than {MAX_LINE_BYTES} bytes")));
        }
        while matches!(self.buf.last(), Some(b'\n' | b'\r')) {
            self.buf.pop();
        }
        match std::str::from_utf8(&self.buf) {
            Ok(text) => Ok(Some(text)),
            Err(_) => Err(CovmapError::Parse {
                file: self.file.clone(),
                line: self.line,
                reason: "not UTF-8 text".into(),
            }),
        }
    }

    /// [`CovmapError::Parse`] at the current line.
    pub(crate) fn error(&self, reason: String) -> CovmapError {
        CovmapError::Parse {
            file: self.file.clone(),
            line: self.line,
            reason,
        }
    }

    /// The file's name as given.
    pub(crate) fn file(&self) -> &str {
        &self.file
    }

    /// The current line's number, from 1.
    pub(crate) fn line(&self) -> usize {
        self.line
    }
}

/// The whitespace-separated fields of one line, read in order, each error
/// naming the field.
pub(crate) struct Fields<'a> {
    tokens: std::str::SplitAsciiWhitespace<'a>,
}

impl<'a> Fields<'a> {
    /// The fields of `line`.
    pub(crate) fn new(line: &'a str) -> Self {
        Self {
            tokens: line.split_ascii_whitespace(),
        }
    }

    /// The next field as text.
    pub(crate) fn word(&mut self, what: &str) -> std::result::Result<&'a str, String> {
        self.tokens
            .next()
            .ok_or_else(|| format!("the line ends before its {what}"))
    }

    /// The next field as a finite number.
    pub(crate) fn number(&mut self, what: &str) -> std::result::Result<f64, String> {
        let word = self.word(what)?;
        match word.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(format!("{what} `{word}` is not a finite number")),
        }
    }

    /// The next field as a count of at most `max`.
    pub(crate) fn count(&mut self, what: &str, max: usize) -> std::result::Result<usize, String> {
        let word = self.word(what)?;
        match word.parse::<usize>() {
            Ok(v) if v <= max => Ok(v),
            _ => Err(format!("{what} `{word}` is not a count from 0 to {max}")),
        }
    }

    /// The fields left, counted.
    pub(crate) fn remaining(&self) -> usize {
        self.tokens.clone().count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn gzip(text: &[u8]) -> Vec<u8> {
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        e.write_all(text).unwrap();
        e.finish().unwrap()
    }

    fn all(mut l: Lines) -> Result<Vec<String>> {
        let mut out = Vec::new();
        while let Some(s) = l.next_line()? {
            out.push(s.to_string());
        }
        Ok(out)
    }

    #[test]
    fn a_device_or_a_directory_is_refused_before_it_is_opened() {
        for path in ["/dev/zero", "/"] {
            let Err(err) = open(Path::new(path)) else {
                panic!("{path} was opened");
            };
            assert!(matches!(err, CovmapError::Io { .. }), "{err}");
            assert!(err.to_string().contains("not a regular file"), "{err}");
        }
    }

    /// A missing file's error keeps the system's error number, which
    /// Python's `OSError.errno` takes.
    #[test]
    fn a_missing_file_keeps_its_errno() {
        let Err(err) = open(Path::new("/nonexistent/covmap-missing.log")) else {
            panic!("a missing file was opened");
        };
        let CovmapError::Io { errno, file, .. } = &err else {
            panic!("{err:?}");
        };
        let kind = errno.map(|n| std::io::Error::from_raw_os_error(n).kind());
        assert_eq!(kind, Some(std::io::ErrorKind::NotFound), "{err}");
        assert_eq!(file, "/nonexistent/covmap-missing.log");
    }

    #[test]
    fn plain_and_gzip_read_the_same_lines() {
        let text = b"a 1\r\nb 2\n\nc";
        let plain = all(lines(std::io::Cursor::new(text.to_vec()), "t").unwrap()).unwrap();
        let zipped = all(lines(std::io::Cursor::new(gzip(text)), "t.gz").unwrap()).unwrap();
        assert_eq!(plain, ["a 1", "b 2", "", "c"]);
        assert_eq!(zipped, plain);
    }

    #[test]
    fn a_truncated_gzip_stream_names_its_file_and_line() {
        let text: Vec<u8> = (0..2000)
            .flat_map(|i| format!("line {i}\n").into_bytes())
            .collect();
        let mut z = gzip(&text);
        z.truncate(z.len() / 2);
        let err = all(lines(std::io::Cursor::new(z), "cut.gz").unwrap()).unwrap_err();
        assert!(
            matches!(&err, CovmapError::Parse { file, line, .. } if file == "cut.gz" && *line > 1),
            "{err}"
        );
    }

    /// A small gzip file of one line repeated, inflating over 1000 times, is
    /// refused early, naming the ratio; a real log's ratio passes.
    #[test]
    fn a_gzip_stream_inflating_beyond_the_ratio_is_refused_early() {
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
        let comment = [b'#'; 1000];
        for _ in 0..20_000 {
            e.write_all(&comment).unwrap();
            e.write_all(b"\n").unwrap();
        }
        let bomb = e.finish().unwrap();
        assert!(
            bomb.len() * 200 < 20_020_000,
            "{} bytes: no bomb",
            bomb.len()
        );
        let mut reader = lines(std::io::Cursor::new(bomb), "bomb.gz").unwrap();
        let mut read = 0;
        let err = loop {
            match reader.next_line() {
                Ok(Some(_)) => read += 1,
                Ok(None) => panic!("the whole bomb was read"),
                Err(e) => break e,
            }
        };
        assert!(err.to_string().contains("more than 100 times"), "{err}");
        // Its first 8 KiB block was read, and what it inflates to.
        assert!(read < 2_000, "{read} lines read before the refusal");
        let numbers: Vec<u8> = (0..20_000u32)
            .flat_map(|i| {
                format!(
                    "FLASER 3 {}.{} 0.5 1 0 0 0 0 0 0 {i} h {i}\n",
                    i % 7,
                    i % 13
                )
                .into_bytes()
            })
            .collect();
        let read = all(lines(std::io::Cursor::new(gzip(&numbers)), "log.gz").unwrap()).unwrap();
        assert_eq!(read.len(), 20_000);
    }

    #[test]
    fn an_endless_line_is_refused_not_held() {
        let long = vec![b'x'; MAX_LINE_BYTES + 10];
        let err = all(lines(std::io::Cursor::new(long), "long").unwrap()).unwrap_err();
        assert!(err.to_string().contains("longer than"), "{err}");
        let bad = all(lines(std::io::Cursor::new(vec![b'a', 0xff, b'\n']), "bin").unwrap());
        assert!(matches!(bad, Err(CovmapError::Parse { line: 1, .. })));
    }

    #[test]
    fn fields_name_what_is_missing_or_wrong() {
        let mut f = Fields::new("3 x nan");
        assert_eq!(f.count("count", 10), Ok(3));
        assert!(f.number("x").unwrap_err().contains("`x`"));
        assert!(f.number("y").unwrap_err().contains("finite"));
        assert!(f.word("z").unwrap_err().contains("ends before its z"));
        assert!(Fields::new("11").count("n", 10).is_err());
    }
}
