//! What is wrong at one place of a matrix file flexmodes reads (Matrix Market, Harwell–Boeing,
//! CalculiX, Abaqus, Nastran DMIG and OP4) or of a DOF map beside it
//! ([`super::BodyFileError::MatrixLine`], which names the file and the line, line 0 the file
//! as a whole; [`super::BodyFileError::MatrixByte`] the byte of a binary OP4).

/// What is wrong at one line (or byte) of a matrix file, with its data. Node numbers and
/// equations are 1-based, as the file writes them.
#[derive(Debug, Clone, PartialEq, thiserror::Error, serde::Serialize)]
pub enum MatrixLineProblem {
    /// A file without a single line.
    #[error("an empty file")]
    EmptyFile,
    /// Harwell–Boeing: a fixed-width field that cuts a character of a section's line (fields
    /// are counted in bytes: the line is not plain ASCII).
    #[error("the {what} line is not plain text")]
    NotPlainText { what: &'static str },
    /// The file, or this line of it, is not UTF-8 text.
    #[error("the file is not text")]
    NotText,
    /// Neither a binary OP4 nor text.
    #[error("neither a binary OP4 (a 24-byte first record) nor text")]
    NeitherOp4NorText,
    /// A file without a single stored entry.
    #[error("the file holds no matrix entries")]
    NoEntries,
    /// The named matrix is not among the file's.
    #[error(
        "no {format} matrix `{wanted}` (the file's {format} matrices: {})",
        listed(found)
    )]
    NoSuchMatrix {
        format: &'static str,
        wanted: super::Name,
        found: Vec<super::Name>,
    },
    /// A named matrix with no entries.
    #[error("`{matrix}` has no entries")]
    MatrixEmpty { matrix: super::Name },

    /// A field that should be a number and is not: `field` what it is, `expected` what kind
    /// of number ("a real number", "an integer", "a count", …).
    #[error("the {field} `{text}` is not {expected}")]
    NotANumber {
        field: &'static str,
        text: super::Excerpt,
        expected: &'static str,
    },
    /// A line that is not laid out as the format's lines are.
    #[error("`{text}`: a line here is `{layout}`")]
    NotLayout {
        text: super::Excerpt,
        layout: &'static str,
    },
    /// A Fortran edit descriptor that cannot be read.
    #[error("the {what} format `{text}` is not a Fortran field such as (1P,3E23.16)")]
    NotAFortranFormat {
        what: &'static str,
        text: super::Excerpt,
    },
    /// A header field naming a kind of matrix that describes no body.
    #[error("{field} `{value}`: {needs}")]
    Unsupported {
        field: &'static str,
        value: super::Excerpt,
        needs: &'static str,
    },

    /// A Matrix Market header without its size line.
    #[error("the size line is missing")]
    SizeLineMissing,
    /// A symmetric matrix whose size line is not square.
    #[error("a symmetric matrix must be square, the file says {rows} × {cols}")]
    NotSquare { rows: usize, cols: usize },
    /// A size line whose rows times columns overflow: more values than any file holds.
    #[error("{rows} × {cols} values are more than any file can hold")]
    SizeOverflow { rows: usize, cols: usize },
    /// A file that ends before the entries (or values, pointers, …) its header announces.
    #[error("the file ends after {read} of the {expected} {what} its header announces")]
    EndsEarly {
        what: &'static str,
        read: usize,
        expected: usize,
    },
    /// Data after the entries the size line announces.
    #[error("`{text}` follows the {expected} {what} the size line announces")]
    TooMany {
        what: &'static str,
        expected: usize,
        text: super::Excerpt,
    },
    /// Harwell–Boeing: the fields read from a section's lines are not as many as its header
    /// says.
    #[error("{found} {what} in {lines} lines, the header says {expected}")]
    CountMismatch {
        what: &'static str,
        found: usize,
        lines: usize,
        expected: usize,
    },
    /// Harwell–Boeing: fewer than four header lines.
    #[error("a Harwell-Boeing file has four header lines, this one {lines}")]
    HeaderShort { lines: usize },
    /// Harwell–Boeing: column pointers that do not run from 1 to the entries + 1.
    #[error("the column pointers run from {first:?} to {last:?}, not from 1 to {expected_last}")]
    PointerRange {
        first: Option<usize>,
        last: Option<usize>,
        expected_last: usize,
    },
    /// Harwell–Boeing: a column whose end pointer lies before its start.
    #[error("column {column}'s pointer decreases ({from} then {to})")]
    PointerDecreases {
        column: usize,
        from: usize,
        to: usize,
    },

    /// Node 0, which no numbering has.
    #[error("node 0 is not a node number (they start at 1)")]
    NodeZero,
    /// A component (DOF) that is neither a displacement nor a rotation.
    #[error(
        "DOF `{component}` of node {node} is not a displacement (1-3, UX UY UZ) or rotation \
         (4-6, ROTX ROTY ROTZ)"
    )]
    NotAComponent {
        node: usize,
        component: super::Excerpt,
    },
    /// A DOF the body's nodes do not carry.
    #[error("node {node} has DOF `{dof}`, which the body's DOF ({}) do not include", body.join(", "))]
    DofNotInBody {
        node: usize,
        dof: super::Excerpt,
        body: Vec<&'static str>,
    },
    /// A node number beyond what FE codes write (and what would size the body).
    #[error("node {node} is beyond the largest node number a matrix file may name, {largest}")]
    NodeNumberTooLarge { node: usize, largest: usize },
    /// A node outside the body's nodes.
    #[error("node {node} is not one of the body's nodes 1 to {count}")]
    NodeNotInBody { node: usize, count: usize },
    /// A DOF map that gives one DOF two equations.
    #[error("node {node} DOF `{dof}` already has equation {before}")]
    DofTwice {
        node: usize,
        dof: super::Excerpt,
        before: usize,
    },
    /// Equation 0 in a map numbered from 1.
    #[error("equations are numbered from 1")]
    EquationZero,
    /// An equation number beyond the body's DOF count (a map gives each DOF one equation).
    #[error("equation {equation} is beyond the body's {count} DOF (one equation per DOF)")]
    EquationBeyond { equation: usize, count: usize },
    /// A DOF map that maps one equation twice.
    #[error("equation {equation} is mapped twice")]
    EquationTwice { equation: usize },
    /// A DOF map without a node and DOF for an equation.
    #[error("no line of the map names equation {equation}")]
    EquationUnplaced { equation: usize },
    /// A DOF of the body without an equation; `left_out` when the FE code leaves out DOF that
    /// are held or belong to no element (CalculiX).
    #[error(
        "node {node} DOF `{dof}` has no equation{}",
        if *left_out {
            " (CalculiX leaves out DOF that are held or belong to no element: write the \
             matrices of an unrestrained part)"
        } else {
            ""
        }
    )]
    DofWithoutEquation {
        node: usize,
        dof: &'static str,
        left_out: bool,
    },
    /// An entry given twice (1-based DOF); in a symmetric file, once per triangle.
    #[error(
        "the entry of DOF {row} and {col} is given twice{}",
        if *symmetric { " (a symmetric DMIG gives one triangle)" } else { "" }
    )]
    EntryTwice {
        row: usize,
        col: usize,
        symmetric: bool,
    },

    /// OP4: the file ends inside a record's length.
    #[error("the file ends inside a record's length")]
    RecordCut,
    /// OP4: a negative record length.
    #[error("record length {length}")]
    RecordLength { length: i64 },
    /// OP4: a record longer than what is left of the file.
    #[error("a record of {length} bytes runs past the end of the file ({file} bytes)")]
    RecordPastEnd { length: usize, file: usize },
    /// OP4: a record whose closing length differs from its opening one.
    #[error("a record of {length} bytes closes with length {trailer}: not an OP4 record")]
    RecordTrailer { length: usize, trailer: i64 },
    /// OP4 with 8-byte integers.
    #[error("an OP4 with 8-byte integers: only 4-byte integers are read")]
    EightByteIntegers,
    /// OP4: a matrix header record of the wrong length.
    #[error("a matrix header of {length} bytes, expected 24 (NCOL NROW NF NTYPE NAME)")]
    HeaderLength { length: usize },
    /// OP4: a matrix without its closing record.
    #[error("`{matrix}` ends before its closing record")]
    NoClosingRecord { matrix: super::Name },
    /// OP4: a column record too short for its header.
    #[error("a column record of {length} bytes")]
    ColumnRecordShort { length: usize },
    /// OP4: a column number below 1.
    #[error("`{matrix}` has no column {column}")]
    NoSuchColumn { matrix: super::Name, column: i64 },
    /// OP4: a row outside the matrix.
    #[error("row {row} of column {column}: `{matrix}` has {rows}")]
    RowOutOfRange {
        matrix: super::Name,
        row: i64,
        column: i64,
        rows: usize,
    },
    /// OP4 (binary): a NaN or infinite value.
    #[error("{value} at row {row}, column {column}")]
    NonFinite { value: f64, row: i64, column: i64 },
    /// OP4 (binary): a dense column whose bytes are not whole values.
    #[error("{length} bytes of values are not whole values")]
    PartValues { length: usize },
    /// OP4 (binary): a string header cut by the end of its column record.
    #[error("a string header runs past its column record")]
    StringHeaderCut,
    /// OP4: a string (of consecutive values) longer than its column.
    #[error("a string of {words} words at row {row} does not fit its column of {column_words}")]
    StringTooLong {
        words: i64,
        row: i64,
        column_words: i64,
    },
    /// OP4 (ASCII): the file ends inside a column.
    #[error("`{matrix}` ends inside column {column}")]
    EndsInsideColumn { matrix: super::Name, column: i64 },
    /// OP4 (ASCII): a line without values where a column's values go on.
    #[error("a line without values inside column {column}")]
    LineWithoutValues { column: i64 },
}

/// `names` joined, or "none".
fn listed(names: &[super::Name]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        super::name::joined(names)
    }
}
