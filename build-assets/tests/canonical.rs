//! The canonical text and cache key of one spec of every kind, of every FAST spatial and
//! temporal filter and of every sample space, pinned: a change to the canonical text re-keys
//! every cache (committed ones included), so it must be a visible, deliberate break (bump the
//! pins and say so in CHANGELOG.md).

use build_assets::cache::key;
use noisebake_test_support::bake::spec;

const PINS: &[(&str, &str, &str)] = &[
    (
        "kind = \"sampler\"\ndims = [32, 32]\nspp = 4\nsample_dims = 4\nsample_space = \"disk\"\nspatial_filter = { kind = \"atrous\", passes = 3 }",
        "kind=sampler;dims=[32,32];seed=0;format=u16;spp=4;sample_dims=4;sample_space=[disk,disk];spatial_filter={kind=atrous,passes=3};temporal_filter={kind=none};frames=1",
        "b08a34301f3e230a0600a1b4a7005f83",
    ),
    (
        "kind = \"fast\"\ndims = [16, 16]\nspatial_filter = { kind = \"atrous\", passes = 2 }",
        "kind=fast;dims=[16,16];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=atrous,passes=2};temporal_filter={kind=none};combine=product;iterations=converged;start=ign",
        "8f4136a150e27fb49850276e3b1b2dbc",
    ),
    (
        "kind = \"sampler\"\ndims = [128, 128]",
        "kind=sampler;dims=[128,128];seed=0;format=u16;spp=1;sample_dims=2;sample_space=[square];spatial_filter={kind=gauss,sigma=1};temporal_filter={kind=none};frames=1",
        "7c28113bcb0437c80b7ad798c4caa750",
    ),
    (
        "kind = \"sampler\"\ndims = [64, 32]\nseed = 3\nspp = 16\nsample_dims = 6\nsample_space = [\"cosine_hemisphere\", \"square\", \"disk\"]\nspatial_filter = { kind = \"box\", size = 5 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1 }\nframes = 4",
        "kind=sampler;dims=[64,32];seed=3;format=u16;spp=16;sample_dims=6;sample_space=[cosine_hemisphere,square,disk];spatial_filter={kind=box,size=5};temporal_filter={kind=ema,alpha=0.1};frames=4",
        "d985f2c77c7fe91453424f03c8955a43",
    ),
    (
        "kind = \"blue2d\"\ndims = [64, 64]",
        "kind=blue2d;dims=[64,64];seed=0;format=u8;sigma=1.5;initial_density=0.1",
        "ad98ffb1e895945b76f6e75019554a35",
    ),
    (
        "kind = \"stbn\"\ndims = [64, 64, 16]\nseed = 7\nformat = \"u16\"",
        "kind=stbn;dims=[64,64,16];seed=7;format=u16;sigma_xy=1.9;sigma_t=1.9;initial_density=0.1;histogram=volume",
        "e543022349d3b5e37a8071ce9c29e8e3",
    ),
    (
        "kind = \"stbn\"\ndims = [32, 32, 8]\nhistogram = \"slice\"\nsigma_xy = 2.1\nsigma_t = 1.5\ninitial_density = 0.2",
        "kind=stbn;dims=[32,32,8];seed=0;format=u8;sigma_xy=2.1;sigma_t=1.5;initial_density=0.2;histogram=slice",
        "3d026de74efcbaf111c89ae400f4bebc",
    ),
    (
        "kind = \"vac\"\ndims = [8, 8, 4, 4]\ngroups = [{ axes = [0, 1] }, { axes = [2], sigma = 1.5 }, { axes = [3] }]\ntoroidal = [true, true, false, true]\nformat = \"f32\"",
        "kind=vac;dims=[8,8,4,4];seed=0;format=f32;groups=[{axes=[0,1],sigma=1.9},{axes=[2],sigma=1.5},{axes=[3],sigma=1.9}];toroidal=[true,true,false,true];initial_density=0.1;histogram=volume",
        "b649a36d043ffb821168a50279bc283d",
    ),
    (
        "kind = \"white\"\ndims = [16, 16, 4]\nseed = 3",
        "kind=white;dims=[16,16,4];seed=3;format=u8",
        "ae32408c89f567834d972a66545c999e",
    ),
    (
        "kind = \"independent2d\"\ndims = [32, 32, 8]",
        "kind=independent2d;dims=[32,32,8];seed=0;format=u8;sigma=1.9;initial_density=0.1",
        "0bada0ad9cc7689e1b9f477ca93ee2cd",
    ),
    (
        "kind = \"golden\"\ndims = [32, 32, 8]\nformat = \"u16\"",
        "kind=golden;dims=[32,32,8];seed=0;format=u16;sigma=1.9;initial_density=0.1",
        "c5f4bcdfe9f5870700ea9c7e6e97b1e1",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32]",
        "kind=fast;dims=[32,32];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=converged;start=ign",
        "a72308bbe75de36e36e4a6b44fa0cb69",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "e5bdc01d14cabc933b964346b4b98df3",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"box\", size = 3 }\ntemporal_filter = { kind = \"box\", size = 4 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=box,size=3};temporal_filter={kind=box,size=4};combine=product;iterations=converged;start=ign",
        "7e482235c4bed6cddeeaaec577db8507",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 16]\nspatial_filter = { kind = \"binomial\", order = 2 }\ntemporal_filter = { kind = \"gauss\", sigma = 1.2 }",
        "kind=fast;dims=[32,32,16];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=binomial,order=2};temporal_filter={kind=gauss,sigma=1.2};combine=product;iterations=converged;start=ign",
        "bdc9c9591860bce7509d6717e26690e7",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"none\" }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }\ncombine = { separate = 0.5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=none};temporal_filter={kind=ema,alpha=0.1,beta=0.1};combine={separate=0.5};iterations=converged;start=ign",
        "813af49124f28e21aee13ab676258893",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"none\" }\niterations = 5\nstart = \"random\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=5;start=random",
        "fdc33edfb55808266a550d35ab72e98e",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"taa\" }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=taa,alpha=0.1,coverage=0.2,motion=[0,0],moving=0};combine=product;iterations=converged;start=ign",
        "182b87128df86a7f166a9b006786267a",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"taa\", motion = [3, -1] }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=taa,alpha=0.1,coverage=0.2,motion=[3,-1],moving=0.25};combine=product;iterations=converged;start=ign",
        "6d159fc5198b366c30188c7d7b43ef1e",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"tent\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=tent;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "6cb8c6f1160fdc327a14a35d4413b748",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"gauss\"\nformat = \"f32\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32;sample_space=scalar;distribution=gauss;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "02eebfc7963f7ac5face048c42d9b7d2",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"circle\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=circle;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "c3221df98be2712984f4a922834393ff",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec2\"\nformat = \"u8x2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x2;sample_space=vec2;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "3a8fcc3af972328c53514997096f8fe3",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec3\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=vec3;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "5c6fc7d32e12cf20084e1843f7e68a5a",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec4\"\nformat = \"u8x4\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x4;sample_space=vec4;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "7cd6576bce67b635b188da26b8078e62",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"sphere\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=sphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "98a431a4fb9909d7a0740d114b6a8335",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"hemisphere\"\nformat = \"f32x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32x3;sample_space=hemisphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "e9aa6e4e1e7dbf7450f89370c7aea466",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=cosine_hemisphere;distribution=uniform;spatial_filter={kind=box,size=5};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign_r2",
        "2c2521df694dc217f58661e4a52998ae",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nstart = \"ign_r2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=cosine_hemisphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign_r2",
        "796bd56f36c78e05287f41c971fa1b8d",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"sphere\"\nformat = \"u8x3\"\nstart = \"rd_ign_r2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=sphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "98a431a4fb9909d7a0740d114b6a8335",
    ),
];

#[test]
fn canonical_texts_and_keys_are_pinned() {
    let mut got = String::new();
    for (body, _, _) in PINS {
        let s = spec(body);
        got += &format!(
            "    (\n        {body:?},\n        {:?},\n        {:?},\n    ),\n",
            s.canonical(),
            key(&s)
        );
    }
    if std::env::var_os("NOISEBAKE_PRINT_PINS").is_some() {
        println!("{got}");
    }
    for (body, text, k) in PINS {
        let s = spec(body);
        assert_eq!(s.canonical(), *text, "{body}");
        assert_eq!(key(&s), *k, "{body}");
    }
}

/// Defaults are filled in: a spec that writes every default out has the canonical text (and so
/// the key) of one that leaves them all out, and the name is not part of it.
#[test]
fn defaults_written_out_change_nothing() {
    for (short, long) in [
        (
            "kind = \"stbn\"\ndims = [16, 16, 4]",
            "kind = \"stbn\"\ndims = [16, 16, 4]\nseed = 0\nformat = \"u8\"\nsigma_xy = 1.9\nsigma_t = 1.9\ninitial_density = 0.1\nhistogram = \"volume\"",
        ),
        (
            "kind = \"fast\"\ndims = [16, 16, 4]",
            "kind = \"fast\"\ndims = [16, 16, 4]\nsample_space = \"scalar\"\ndistribution = \"uniform\"\nspatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0 }\ncombine = \"product\"\nstart = \"ign\"",
        ),
    ] {
        assert_eq!(spec(short).canonical(), spec(long).canonical());
    }
    let renamed = build_assets::spec::parse_toml(
        "[[texture]]\nname = \"OTHER\"\nkind = \"white\"\ndims = [4]\n",
    )
    .unwrap()
    .textures
    .remove(0);
    assert_eq!(
        renamed.canonical(),
        spec("kind = \"white\"\ndims = [4]").canonical()
    );
}

/// Every pinned canonical text reads back to its spec: `to_spec` then `canonical` is the
/// identity, which is how `cache verify` knows an entry's text is this version's.
#[test]
fn canonical_text_reads_back() {
    for (_, text, _) in PINS {
        let back =
            build_assets::spec::canonical::to_spec(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(back.canonical(), *text);
    }
    // Text in the pre-0.1 Debug form does not.
    assert!(build_assets::spec::canonical::to_spec(
        "kind=fast;dims=[16,16,4];seed=0;format=u8;sample_space=scalar;distribution=Uniform;spatial=Gauss { sigma: 1.3435 }"
    )
    .is_err());
}
