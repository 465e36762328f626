//! Table rows (the serde structs the CSV files are written from) gathered into typed columns,
//! for the Python package: the same columns under the same names as the CSV, each number the
//! one its written digits say ([`super::written`]), without writing and reading the text. A serde `Serializer` written
//! here because the one crate that does this (serde_arrow) would bring Arrow with it.
//!
//! [`super::Num`] writes its text to human-readable formats (CSV, JSON) and the number
//! of that text to this one, which says it is not human-readable.

use serde::ser::{self, Impossible, Serialize};

/// One column's values.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// Numbers (NaN where the CSV has an empty cell).
    Num(Vec<f64>),
    /// Counts.
    Int(Vec<i64>),
    /// Switches.
    Bool(Vec<bool>),
    /// Text.
    Text(Vec<String>),
}

/// Named columns of equal length, in the CSV's order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    /// Each column's name (the CSV's header).
    pub names: Vec<String>,
    /// The columns.
    pub columns: Vec<Column>,
}

/// Gathers rows into a table.
pub fn table<T: Serialize>(rows: impl IntoIterator<Item = T>) -> Result<Table, Error> {
    let mut t = Table::default();
    for (i, r) in rows.into_iter().enumerate() {
        let mut sink = Row {
            table: &mut t,
            field: 0,
            first: i == 0,
        };
        r.serialize(&mut sink)?;
        if sink.field != sink.table.columns.len() {
            return Err(Error(format!(
                "row {i} has {} fields, the first {}",
                sink.field,
                sink.table.columns.len()
            )));
        }
    }
    Ok(t)
}

/// Why rows could not be gathered (a row type this module does not take).
#[derive(Debug)]
pub struct Error(String);

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Error {}

impl ser::Error for Error {
    fn custom<T: std::fmt::Display>(msg: T) -> Self {
        Error(msg.to_string())
    }
}

/// A row being gathered: its next field's column.
struct Row<'a> {
    table: &'a mut Table,
    field: usize,
    first: bool,
}

impl Row<'_> {
    /// Adds a field's value (on the first row, its column).
    fn push(&mut self, name: &str, value: Value) -> Result<(), Error> {
        if self.first {
            self.table.names.push(name.to_string());
            self.table.columns.push(match value {
                Value::Num(_) => Column::Num(Vec::new()),
                Value::Int(_) => Column::Int(Vec::new()),
                Value::Bool(_) => Column::Bool(Vec::new()),
                Value::Text(_) => Column::Text(Vec::new()),
            });
        }
        let column = self
            .table
            .columns
            .get_mut(self.field)
            .ok_or_else(|| Error(format!("field {name}: more fields than the first row")))?;
        match (column, value) {
            (Column::Num(c), Value::Num(v)) => c.push(v),
            (Column::Int(c), Value::Int(v)) => c.push(v),
            // A count left empty (an `Option` that is None) in some rows: a column of numbers,
            // NaN where it is empty, as pandas makes it of the CSV.
            (Column::Num(c), Value::Int(v)) => c.push(v as f64),
            (column @ Column::Int(_), Value::Num(v)) if v.is_nan() => {
                let Column::Int(counts) = &*column else { unreachable!() };
                let mut numbers: Vec<f64> = counts.iter().map(|&x| x as f64).collect();
                numbers.push(v);
                *column = Column::Num(numbers);
            }
            (Column::Bool(c), Value::Bool(v)) => c.push(v),
            (Column::Text(c), Value::Text(v)) => c.push(v),
            _ => return Err(Error(format!("field {name}: another type than in the first row"))),
        }
        self.field += 1;
        Ok(())
    }
}

/// One field's value.
enum Value {
    Num(f64),
    Int(i64),
    Bool(bool),
    Text(String),
}

/// Serializes one field's value.
struct Field;

macro_rules! unsupported {
    ($($name:ident($($arg:ty),*)),* $(,)?) => {
        $(fn $name(self, $(_: $arg),*) -> Result<Self::Ok, Error> {
            Err(Error(concat!("a table cell cannot be ", stringify!($name)).into()))
        })*
    };
}

/// The compound forms (lists, maps, tuples, enums with data) a serializer here refuses, each
/// with `$what` in its message.
macro_rules! refuse_compound {
    ($ok:ty, $what:literal) => {
        fn serialize_newtype_variant<T: Serialize + ?Sized>(
            self,
            _: &'static str,
            _: u32,
            _: &'static str,
            _: &T,
        ) -> Result<$ok, Error> {
            Err(Error(concat!($what, " an enum with data").into()))
        }
        fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, Error> {
            Err(Error(concat!($what, " a list").into()))
        }
        fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Self::SerializeTupleStruct, Error> {
            Err(Error(concat!($what, " a tuple").into()))
        }
        fn serialize_tuple_variant(
            self,
            _: &'static str,
            _: u32,
            _: &'static str,
            _: usize,
        ) -> Result<Self::SerializeTupleVariant, Error> {
            Err(Error(concat!($what, " an enum with data").into()))
        }
        fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, Error> {
            Err(Error(concat!($what, " a map").into()))
        }
        fn serialize_struct_variant(
            self,
            _: &'static str,
            _: u32,
            _: &'static str,
            _: usize,
        ) -> Result<Self::SerializeStructVariant, Error> {
            Err(Error(concat!($what, " an enum with data").into()))
        }
    };
}

impl ser::Serializer for Field {
    type Ok = Value;
    type Error = Error;
    type SerializeSeq = Impossible<Value, Error>;
    type SerializeTuple = Impossible<Value, Error>;
    type SerializeTupleStruct = Impossible<Value, Error>;
    type SerializeTupleVariant = Impossible<Value, Error>;
    type SerializeMap = Impossible<Value, Error>;
    type SerializeStruct = Impossible<Value, Error>;
    type SerializeStructVariant = Impossible<Value, Error>;

    fn is_human_readable(&self) -> bool {
        false
    }
    fn serialize_f64(self, v: f64) -> Result<Value, Error> {
        Ok(Value::Num(v))
    }
    fn serialize_f32(self, v: f32) -> Result<Value, Error> {
        Ok(Value::Num(v.into()))
    }
    fn serialize_none(self) -> Result<Value, Error> {
        Ok(Value::Num(f64::NAN))
    }
    fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> Result<Value, Error> {
        v.serialize(self)
    }
    fn serialize_u64(self, v: u64) -> Result<Value, Error> {
        i64::try_from(v)
            .map(Value::Int)
            .map_err(|_| Error(format!("{v} is too large a count")))
    }
    fn serialize_i64(self, v: i64) -> Result<Value, Error> {
        Ok(Value::Int(v))
    }
    fn serialize_u32(self, v: u32) -> Result<Value, Error> {
        Ok(Value::Int(v.into()))
    }
    fn serialize_i32(self, v: i32) -> Result<Value, Error> {
        Ok(Value::Int(v.into()))
    }
    fn serialize_bool(self, v: bool) -> Result<Value, Error> {
        Ok(Value::Bool(v))
    }
    fn serialize_str(self, v: &str) -> Result<Value, Error> {
        Ok(Value::Text(v.to_string()))
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, variant: &'static str) -> Result<Value, Error> {
        Ok(Value::Text(variant.to_string()))
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> Result<Value, Error> {
        v.serialize(self)
    }
    unsupported!(
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_char(char),
        serialize_bytes(&[u8]),
        serialize_unit(),
        serialize_unit_struct(&'static str),
    );
    refuse_compound!(Value, "a table cell cannot be");
    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, Error> {
        Err(Error("a table cell cannot be a tuple".into()))
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self::SerializeStruct, Error> {
        Err(Error("a table cell cannot be a struct".into()))
    }
}

/// A row is a struct of cells, or a tuple of such structs (their fields one after another, as
/// the CSV writer puts them).
impl<'a, 'b> ser::Serializer for &'a mut Row<'b> {
    type Ok = ();
    type Error = Error;
    type SerializeSeq = Impossible<(), Error>;
    type SerializeTuple = Self;
    type SerializeTupleStruct = Impossible<(), Error>;
    type SerializeTupleVariant = Impossible<(), Error>;
    type SerializeMap = Impossible<(), Error>;
    type SerializeStruct = Self;
    type SerializeStructVariant = Impossible<(), Error>;

    fn is_human_readable(&self) -> bool {
        false
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self, Error> {
        Ok(self)
    }
    fn serialize_tuple(self, _: usize) -> Result<Self, Error> {
        Ok(self)
    }
    unsupported!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_f32(f32),
        serialize_f64(f64),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
        serialize_none(),
        serialize_unit(),
        serialize_unit_struct(&'static str),
        serialize_unit_variant(&'static str, u32, &'static str),
    );
    fn serialize_some<T: Serialize + ?Sized>(self, _: &T) -> Result<(), Error> {
        Err(Error("a row must be a struct".into()))
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> Result<(), Error> {
        v.serialize(self)
    }
    refuse_compound!((), "a row must be a struct, not");
}

impl ser::SerializeStruct for &mut Row<'_> {
    type Ok = ();
    type Error = Error;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), Error> {
        let v = value.serialize(Field)?;
        self.push(key, v)
    }
    fn end(self) -> Result<(), Error> {
        Ok(())
    }
}

impl ser::SerializeTuple for &mut Row<'_> {
    type Ok = ();
    type Error = Error;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), Error> {
        value.serialize(&mut **self)
    }
    fn end(self) -> Result<(), Error> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::{csv_rows, Num};

    #[derive(serde::Serialize)]
    struct A {
        x: Num,
        n: usize,
        s: String,
        b: bool,
    }

    #[derive(serde::Serialize)]
    struct B {
        y: Num,
    }

    /// The columns are the CSV's, under its header's names; the numbers those the CSV writes,
    /// NaN where it leaves a cell empty (no value, or one that is not finite).
    #[test]
    fn a_table_has_the_csvs_columns_and_the_unrounded_numbers() {
        let rows = || {
            [(1.0 / 3.0, None), (2.5, Some(f64::INFINITY))].map(|(x, y)| {
                (
                    A {
                        x: x.into(),
                        n: 7,
                        s: "a,b".into(),
                        b: true,
                    },
                    B { y: Num(y) },
                )
            })
        };
        let t = table(rows()).unwrap();
        let csv = String::from_utf8(csv_rows(rows(), true).unwrap()).unwrap();
        assert_eq!(csv.lines().next().unwrap(), t.names.join(","));
        assert_eq!(t.names, ["x", "n", "s", "b", "y"]);
        assert_eq!(t.columns[0], Column::Num(vec![0.3333333, 2.5]));
        assert!(csv.contains("0.3333333,7"));
        assert_eq!(t.columns[1], Column::Int(vec![7, 7]));
        assert_eq!(t.columns[2], Column::Text(vec!["a,b".into(), "a,b".into()]));
        assert_eq!(t.columns[3], Column::Bool(vec![true, true]));
        let Column::Num(y) = &t.columns[4] else { panic!() };
        assert!(y[0].is_nan() && y[1].is_nan());
    }

    /// A count some rows leave empty (a point without a solution has no count of unconverged
    /// stations) is a column of numbers, NaN where it is empty, whichever row comes first.
    #[test]
    fn a_count_left_empty_in_some_rows_is_a_column_of_numbers() {
        #[derive(serde::Serialize)]
        struct C {
            n: Option<usize>,
        }
        for (rows, want) in [
            ([Some(2), None, Some(0)], [2.0, f64::NAN, 0.0]),
            ([None, Some(3), None], [f64::NAN, 3.0, f64::NAN]),
        ] {
            let t = table(rows.map(|n| C { n })).unwrap();
            let Column::Num(got) = &t.columns[0] else {
                panic!("{:?}", t.columns[0])
            };
            assert!(
                got.iter().zip(want).all(|(a, b)| a == &b || (a.is_nan() && b.is_nan())),
                "{got:?}"
            );
        }
        let t = table([Some(1), Some(2)].map(|n| C { n })).unwrap();
        assert_eq!(t.columns[0], Column::Int(vec![1, 2]));
    }

    #[test]
    fn a_row_that_is_not_a_struct_is_an_error() {
        assert!(table([1.0]).is_err());
        assert!(table([vec![1.0]]).is_err());
    }
}
